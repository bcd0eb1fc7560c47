// Bandwidth ceiling kernels: a streaming read (sum of a large buffer) and a copy. They measure the
// device's own memory bandwidth in the same run as the relighting kernels.
__kernel void read_sum(__global const float4* input, const uint count, __global float* partial) {
  const uint gid = get_global_id(0);
  const uint stride = get_global_size(0);
  float4 acc = (float4)(0.0f);
  for (uint i = gid; i < count; i += stride) acc += input[i];
  partial[gid] = acc.x + acc.y + acc.z + acc.w;
}

__kernel void copy(__global const float4* input, __global float4* output, const uint count) {
  const uint gid = get_global_id(0);
  const uint stride = get_global_size(0);
  for (uint i = gid; i < count; i += stride) output[i] = input[i];
}
