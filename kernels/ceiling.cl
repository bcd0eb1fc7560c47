// Bandwidth ceiling kernels: a streaming read (sum of a large buffer) and a copy, each in two
// access patterns. "blocked": every work-item walks its own contiguous run of float4, which
// streams well on CPU devices (PoCL runs a work-group as a loop over its work-items). "strided":
// consecutive work-items touch consecutive float4 (a grid-stride loop), which coalesces on GPUs.
// The host measures both and keeps the faster: the device's own best bandwidth.

#ifndef RUN_LENGTH
#define RUN_LENGTH 16  // float4 per work-item in the blocked kernels
#endif

__kernel void read_sum_blocked(__global const float4* input, __global float* partial) {
  const size_t gid = get_global_id(0);
  __global const float4* run = input + gid * RUN_LENGTH;
  float4 acc = (float4)(0.0f);
  for (int i = 0; i < RUN_LENGTH; ++i) acc += run[i];
  partial[gid] = acc.x + acc.y + acc.z + acc.w;
}

__kernel void read_sum_strided(__global const float4* input, const uint count,
                               __global float* partial) {
  const uint gid = get_global_id(0);
  const uint stride = get_global_size(0);
  float4 acc = (float4)(0.0f);
  for (uint i = gid; i < count; i += stride) acc += input[i];
  partial[gid] = acc.x + acc.y + acc.z + acc.w;
}

__kernel void copy_blocked(__global const float4* input, __global float4* output) {
  const size_t first = get_global_id(0) * RUN_LENGTH;
  for (int i = 0; i < RUN_LENGTH; ++i) output[first + i] = input[first + i];
}

__kernel void copy_strided(__global const float4* input, __global float4* output,
                           const uint count) {
  const uint gid = get_global_id(0);
  const uint stride = get_global_size(0);
  for (uint i = gid; i < count; i += stride) output[i] = input[i];
}
