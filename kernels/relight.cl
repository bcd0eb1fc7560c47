// Relighting kernels for a compressed reflectance field (lib/relight/opencl_relighter.cpp uploads the data
// and sets the defines below). BATCH light vectors are relit in one pass over W and E.
//
//   cluster_products: v[k][j][c][b] = sum_i F^k[j][i] * I[i][c][b], every cluster in one launch.
//     F^k is stored in 2x2 blocks as float4 (rows 2jb, 2jb+1 x lights 2ib, 2ib+1), zero-padded
//     to even terms and lights ("NV-Single" blocking); one work-item per (cluster, row pair,
//     group of frames).
//   relight_rows: out[b][p] = W[s] . v[k][.][c][b]
//                             + sum_{e < min(width, cap)} E[s][e] * I[i_e][c][b]
//   residual_rows: the residual term alone (the residual SpMV).
//   dark_pixels: out[b][q * CHANNELS + c] = gain[d][c] * dark[c][b] for the pixels of the dark
//     model (d: the pixel's index among them), whose per-channel values the host computes per
//     frame (dark[c] . I); one work-item per run of consecutive dark pixels (runs[3r] first pixel,
//     runs[3r + 1] pixels, runs[3r + 2] the first one's index d).
//     One work-item per stored row s (function p, channel c = p % CHANNELS, cluster k). Rows are
//     grouped in slices of SLICE_ROWS; W is stored slot-major in blocks of WEIGHT_ROWS rows (a
//     divisor of SLICE_ROWS: all of a block's rows' term j, then term j+1), so consecutive
//     work-items read consecutive addresses. The residual
//     (lib/relight/relight_layout.hpp) has a head, entries [0, HEAD_ENTRIES) in the slices, and with
//     TAIL_ROWS > 0 a tail, the later entries in groups of TAIL_ROWS rows; each group is stored
//     slot-major too (all rows' entry e, then e+1) and padded with zero entries to the width of
//     its longest row: reading a padded entry adds 0 * I[0]. Per-row arrays are padded to whole
//     slices.
//     With BATCH == 1 and ROW_VECTOR > 1 (CPU devices), a work-item relights ROW_VECTOR
//     consecutive rows of a slice with vector loads and gathers; otherwise a work-item relights
//     one row for all frames, the frames forming vectors of BATCH_WIDTH.
//
// WORK_CEILING builds relight_rows as the relighter's work ceiling: the same row kernel, same
// shape, precision and residual widths, but every read confined to the first WINDOW_ROWS rows'
// data (a window that stays in cache) and no output written unless a sum is NaN, so that it
// times the gathers, conversions and multiply-adds per row without the memory traffic
// (relume bench's second roof; lib/relight/opencl_relighter.hpp, work_ceiling_seconds).
//
// W and the residual values are WEIGHT_T and RESIDUAL_T: float, or the integers of a quantized
// field (char or short) whose steps the host folded into the blocks and the light vector
// (lib/relight/relight_layout.hpp), so the kernels only convert them to float.
//
// Light vectors: light[(i * CHANNELS + c) * BATCH_PAD + b], lights padded to even with zeros.
// Products:      v[((k * TERMS + j) * CHANNELS + c) * BATCH_PAD + b].
// Output:        out[b * frame_stride + p]; functions that are not stored are never written. The
//                host pads frame_stride so that the frames' write streams do not alias in cache.

#ifndef TERMS
#define TERMS 4
#endif
#ifndef CHANNELS
#define CHANNELS 3
#endif
#ifndef BATCH
#define BATCH 1  // frames relit per pass
#endif
#ifndef BATCH_WIDTH
#define BATCH_WIDTH 1  // frames per vector: 1, 2, 4, 8 or 16
#endif
#ifndef SLICE_ROWS
#define SLICE_ROWS 32
#endif
#ifndef WEIGHT_ROWS
#define WEIGHT_ROWS SLICE_ROWS
#endif
#ifndef CLUSTER_T
#define CLUSTER_T uint
#endif
#ifndef LIGHT_T
#define LIGHT_T uint
#endif
#ifndef WEIGHT_T
#define WEIGHT_T float  // or char / short: quantized W
#endif
#ifndef RESIDUAL_T
#define RESIDUAL_T float  // or char / short: quantized residual values
#endif
#ifndef ROW_VECTOR
#define ROW_VECTOR 1  // rows per work-item when BATCH == 1: 1, 4, 8 or 16
#endif
#ifndef TAIL_ROWS
#define TAIL_ROWS 0  // rows per group of the residual's tail; 0: no tail
#endif
#ifndef HEAD_ENTRIES
#define HEAD_ENTRIES 0xffffffffu  // residual entries per row in the slices
#endif

#ifdef WORK_CEILING
// Where a row's data is read: inside the window. `group_rows`: the rows of a residual group.
#define DATA_ROW(row) ((row) % WINDOW_ROWS)
#define GROUP_OFFSET(offsets, group) ((offsets)[0])
#define IN_GROUP(row, group_rows) (((row) % (group_rows)) % WINDOW_ROWS)
#else
#define DATA_ROW(row) (row)
#define GROUP_OFFSET(offsets, group) ((offsets)[group])
#define IN_GROUP(row, group_rows) ((row) % (group_rows))
#endif

#define BATCH_VECTORS ((BATCH + BATCH_WIDTH - 1) / BATCH_WIDTH)
#define BATCH_PAD (BATCH_VECTORS * BATCH_WIDTH)
#define TERM_PAIRS ((TERMS + 1) / 2)

#if BATCH_WIDTH == 1
typedef float frames;
#define load_frames(pointer) (*(pointer))
#define store_frames(value, pointer) (*(pointer) = (value))
#elif BATCH_WIDTH == 2
typedef float2 frames;
#define load_frames(pointer) vload2(0, pointer)
#define store_frames(value, pointer) vstore2(value, 0, pointer)
#elif BATCH_WIDTH == 4
typedef float4 frames;
#define load_frames(pointer) vload4(0, pointer)
#define store_frames(value, pointer) vstore4(value, 0, pointer)
#elif BATCH_WIDTH == 8
typedef float8 frames;
#define load_frames(pointer) vload8(0, pointer)
#define store_frames(value, pointer) vstore8(value, 0, pointer)
#elif BATCH_WIDTH == 16
typedef float16 frames;
#define load_frames(pointer) vload16(0, pointer)
#define store_frames(value, pointer) vstore16(value, 0, pointer)
#else
#error "BATCH_WIDTH must be 1, 2, 4, 8 or 16"
#endif
#if BATCH_WIDTH == 1
#define any_nan(value) isnan(value)
#else
#define any_nan(value) any(isnan(value))
#endif

#if TERMS > 0  // a residual-only field has no basis products
// Global size: clusters * TERM_PAIRS * BATCH_VECTORS.
__kernel void cluster_products(const uint light_pairs, __global const float4* blocks,
                               __global const float* light, __global float* products) {
  const uint gid = get_global_id(0);
  const uint vector = gid % BATCH_VECTORS;
  const uint pair = (gid / BATCH_VECTORS) % TERM_PAIRS;
  const uint k = gid / (BATCH_VECTORS * TERM_PAIRS);
  __global const float4* block = blocks + (k * TERM_PAIRS + pair) * light_pairs;
  __global const float* frames_of = light + vector * BATCH_WIDTH;
  frames upper[CHANNELS], lower[CHANNELS];
  for (int c = 0; c < CHANNELS; ++c) upper[c] = lower[c] = (frames)(0.0f);
  for (uint ib = 0; ib < light_pairs; ++ib) {
    const float4 f = block[ib];
    for (int c = 0; c < CHANNELS; ++c) {
      const frames even = load_frames(frames_of + ((2 * ib) * CHANNELS + c) * BATCH_PAD);
      const frames odd = load_frames(frames_of + ((2 * ib + 1) * CHANNELS + c) * BATCH_PAD);
      upper[c] += f.x * even + f.y * odd;
      lower[c] += f.z * even + f.w * odd;
    }
  }
  const uint j = 2 * pair;
  for (int c = 0; c < CHANNELS; ++c) {
    store_frames(upper[c],
                 products + ((k * TERMS + j) * CHANNELS + c) * BATCH_PAD + vector * BATCH_WIDTH);
    if (j + 1 < TERMS)
      store_frames(lower[c], products + ((k * TERMS + j + 1) * CHANNELS + c) * BATCH_PAD +
                                 vector * BATCH_WIDTH);
  }
}
#endif

// Adds the first min(group width, cap) entries of `row` in one residual region (groups of
// group_rows rows starting at offsets[row / group_rows]) times the light vector.
inline void add_region(const uint row, const uint group_rows, const uint c, const uint cap,
                       __global const uint* offsets, __global const RESIDUAL_T* residual_values,
                       __global const LIGHT_T* residual_lights, __global const float* light,
                       frames* sums) {
  const uint group = row / group_rows;
  const uint begin = GROUP_OFFSET(offsets, group) + IN_GROUP(row, group_rows);
  const uint used = min((offsets[group + 1] - offsets[group]) / group_rows, cap);
  for (uint e = 0; e < used; ++e) {
    const float value = (float)residual_values[begin + e * group_rows];
    __global const float* frames_of =
        light + (residual_lights[begin + e * group_rows] * CHANNELS + c) * BATCH_PAD;
    for (int v = 0; v < BATCH_VECTORS; ++v)
      sums[v] += value * load_frames(frames_of + v * BATCH_WIDTH);
  }
}

// Adds the first `cap` residual entries of `row` (head, then tail) times the light vector.
inline void add_residual(const uint row, const uint c, const uint cap,
                         __global const uint* slice_offsets, __global const uint* tail_offsets,
                         __global const RESIDUAL_T* residual_values,
                         __global const LIGHT_T* residual_lights, __global const float* light,
                         frames* sums) {
  add_region(row, SLICE_ROWS, c, cap, slice_offsets, residual_values, residual_lights, light,
             sums);
#if TAIL_ROWS > 0
  if (cap > HEAD_ENTRIES)
    add_region(row, TAIL_ROWS, c, cap - HEAD_ENTRIES, tail_offsets, residual_values,
               residual_lights, light, sums);
#endif
}

inline void write_frames(const uint p, const uint frame_stride, const frames* sums,
                         __global float* output) {
#ifdef WORK_CEILING
  // Every frame's sum decides, so that none of them can be left uncomputed.
  frames total = sums[0];
  for (int v = 1; v < BATCH_VECTORS; ++v) total += sums[v];
  if (!any_nan(total)) return;
#endif
#if BATCH == 1
  output[p] = sums[0];
#else
  float lanes[BATCH_PAD];
  for (int v = 0; v < BATCH_VECTORS; ++v) store_frames(sums[v], lanes + v * BATCH_WIDTH);
  __global float* out = output + p;
#pragma unroll
  for (int b = 0; b < BATCH; ++b) out[b * frame_stride] = lanes[b];
#endif
}

#if BATCH == 1 && ROW_VECTOR > 1
#define ROW_CAT_(a, b) a##b
#define ROW_CAT(a, b) ROW_CAT_(a, b)
typedef ROW_CAT(float, ROW_VECTOR) row_floats;
typedef ROW_CAT(uint, ROW_VECTOR) row_uints;
// Gather indices are signed: 32-bit signed lanes let the compiler use dword-indexed gathers.
typedef ROW_CAT(int, ROW_VECTOR) row_ints;
#define load_rows(pointer) ROW_CAT(vload, ROW_VECTOR)(0, pointer)
// ROW_VECTOR values of any type (float, or a quantized field's char / short) as floats.
#define load_row_floats(pointer) ROW_CAT(convert_float, ROW_VECTOR)(load_rows(pointer))
#define store_rows(value, pointer) ROW_CAT(vstore, ROW_VECTOR)(value, 0, pointer)
#define to_row_ints(value) ROW_CAT(convert_int, ROW_VECTOR)(value)
#if ROW_VECTOR == 4
#define gather(base, i) (float4)(base[i.s0], base[i.s1], base[i.s2], base[i.s3])
#elif ROW_VECTOR == 8
#define gather(base, i)                                                                        \
  (float8)(base[i.s0], base[i.s1], base[i.s2], base[i.s3], base[i.s4], base[i.s5], base[i.s6], \
           base[i.s7])
#elif ROW_VECTOR == 16
#define gather(base, i)                                                                         \
  (float16)(base[i.s0], base[i.s1], base[i.s2], base[i.s3], base[i.s4], base[i.s5], base[i.s6], \
            base[i.s7], base[i.s8], base[i.s9], base[i.sa], base[i.sb], base[i.sc], base[i.sd], \
            base[i.se], base[i.sf])
#else
#error "ROW_VECTOR must be 1, 4, 8 or 16"
#endif

// One residual entry of ROW_VECTOR rows times the light vector.
inline row_floats residual_term(const uint entry, const row_ints c,
                                __global const RESIDUAL_T* residual_values,
                                __global const LIGHT_T* residual_lights,
                                __global const float* light) {
  const row_ints index = to_row_ints(load_rows(residual_lights + entry)) * CHANNELS + c;
  return load_row_floats(residual_values + entry) * gather(light, index);
}

// The first min(group width, cap) entries of ROW_VECTOR rows starting at `first` (inside one
// group) in one residual region (groups of group_rows rows) times the light vector.
inline row_floats region_of_rows(const uint first, const uint group_rows, const row_ints c,
                                 const uint cap, __global const uint* offsets,
                                 __global const RESIDUAL_T* residual_values,
                                 __global const LIGHT_T* residual_lights,
                                 __global const float* light) {
  const uint group = first / group_rows;
  const uint begin = GROUP_OFFSET(offsets, group) + IN_GROUP(first, group_rows);
  const uint used = min((offsets[group + 1] - offsets[group]) / group_rows, cap);
  // Two sums, so that consecutive entries' gathers and multiply-adds overlap.
  row_floats even = (row_floats)(0.0f), odd = (row_floats)(0.0f);
  uint e = 0;
  for (; e + 1 < used; e += 2) {
    even += residual_term(begin + e * group_rows, c, residual_values, residual_lights, light);
    odd += residual_term(begin + (e + 1) * group_rows, c, residual_values, residual_lights, light);
  }
  if (e < used)
    even += residual_term(begin + e * group_rows, c, residual_values, residual_lights, light);
  return even + odd;
}

// Residual term of ROW_VECTOR rows starting at `first`: the head, then the tail.
inline row_floats residual_of_rows(const uint first, const row_ints c, const uint cap,
                                   __global const uint* slice_offsets,
                                   __global const uint* tail_offsets,
                                   __global const RESIDUAL_T* residual_values,
                                   __global const LIGHT_T* residual_lights,
                                   __global const float* light) {
  row_floats sums = region_of_rows(first, SLICE_ROWS, c, cap, slice_offsets, residual_values,
                                   residual_lights, light);
#if TAIL_ROWS > 0
  if (cap > HEAD_ENTRIES)
    sums += region_of_rows(first, TAIL_ROWS, c, cap - HEAD_ENTRIES, tail_offsets,
                           residual_values, residual_lights, light);
#endif
  return sums;
}

// Writes ROW_VECTOR rows' outputs: one vector store when their functions are consecutive.
inline void write_rows(const uint first, const uint rows, const row_uints p, const row_floats sums,
                       __global float* output) {
#ifdef WORK_CEILING
  if (!any(isnan(sums))) return;
#endif
  uint functions_of[ROW_VECTOR];
  store_rows(p, functions_of);
  if (first + ROW_VECTOR <= rows &&
      functions_of[ROW_VECTOR - 1] - functions_of[0] == ROW_VECTOR - 1) {
    store_rows(sums, output + functions_of[0]);
    return;
  }
  float values[ROW_VECTOR];
  store_rows(sums, values);
  for (int l = 0; l < ROW_VECTOR; ++l)
    if (first + l < rows) output[functions_of[l]] = values[l];
}

__kernel void relight_rows(const uint rows, const uint frame_stride, const uint cap,
                           __global const uint* stored_function, __global const CLUSTER_T* cluster,
                           __global const WEIGHT_T* weights, __global const float* products,
                           __global const uint* slice_offsets,
                           __global const uint* tail_offsets,
                           __global const RESIDUAL_T* residual_values,
                           __global const LIGHT_T* residual_lights, __global const float* light,
                           __global float* output) {
  const uint first = get_global_id(0) * ROW_VECTOR;
  if (first >= rows) return;
  const uint at = DATA_ROW(first);
  const row_uints p = load_rows(stored_function + at);
  const row_ints c = to_row_ints(p % CHANNELS);
  const row_ints product_index = to_row_ints(load_rows(cluster + at)) * (TERMS * CHANNELS) + c;
  __global const WEIGHT_T* row_weights =
      weights + (at / WEIGHT_ROWS) * (TERMS * WEIGHT_ROWS) + at % WEIGHT_ROWS;
  row_floats sums =
      residual_of_rows(first, c, cap, slice_offsets, tail_offsets, residual_values, residual_lights,
                       light);
  for (int j = 0; j < TERMS; ++j) {
    const row_ints index = product_index + j * CHANNELS;
    sums += load_row_floats(row_weights + j * WEIGHT_ROWS) * gather(products, index);
  }
  write_rows(first, rows, p, sums, output);
}

__kernel void residual_rows(const uint rows, const uint frame_stride, const uint cap,
                            __global const uint* stored_function,
                            __global const uint* slice_offsets,
                            __global const uint* tail_offsets,
                            __global const RESIDUAL_T* residual_values,
                            __global const LIGHT_T* residual_lights, __global const float* light,
                            __global float* output) {
  const uint first = get_global_id(0) * ROW_VECTOR;
  if (first >= rows) return;
  const row_uints p = load_rows(stored_function + first);
  const row_floats sums =
      residual_of_rows(first, to_row_ints(p % CHANNELS), cap, slice_offsets, tail_offsets,
                       residual_values, residual_lights, light);
  write_rows(first, rows, p, sums, output);
}

#else

__kernel void relight_rows(const uint rows, const uint frame_stride, const uint cap,
                           __global const uint* stored_function, __global const CLUSTER_T* cluster,
                           __global const WEIGHT_T* weights, __global const float* products,
                           __global const uint* slice_offsets,
                           __global const uint* tail_offsets,
                           __global const RESIDUAL_T* residual_values,
                           __global const LIGHT_T* residual_lights, __global const float* light,
                           __global float* output) {
  const uint row = get_global_id(0);
  if (row >= rows) return;
  const uint at = DATA_ROW(row);
  const uint p = stored_function[at];
  const uint c = p % CHANNELS;
  __global const float* row_products =
      products + ((uint)cluster[at] * TERMS * CHANNELS + c) * BATCH_PAD;
  __global const WEIGHT_T* row_weights =
      weights + (at / WEIGHT_ROWS) * (TERMS * WEIGHT_ROWS) + at % WEIGHT_ROWS;
  frames sums[BATCH_VECTORS];
  for (int v = 0; v < BATCH_VECTORS; ++v) sums[v] = (frames)(0.0f);
  for (int j = 0; j < TERMS; ++j) {
    const float w = (float)row_weights[j * WEIGHT_ROWS];
    for (int v = 0; v < BATCH_VECTORS; ++v)
      sums[v] += w * load_frames(row_products + j * CHANNELS * BATCH_PAD + v * BATCH_WIDTH);
  }
  add_residual(row, c, cap, slice_offsets, tail_offsets, residual_values, residual_lights, light,
               sums);
  write_frames(p, frame_stride, sums, output);
}

__kernel void residual_rows(const uint rows, const uint frame_stride, const uint cap,
                            __global const uint* stored_function,
                            __global const uint* slice_offsets,
                            __global const uint* tail_offsets,
                            __global const RESIDUAL_T* residual_values,
                            __global const LIGHT_T* residual_lights, __global const float* light,
                            __global float* output) {
  const uint row = get_global_id(0);
  if (row >= rows) return;
  const uint p = stored_function[row];
  frames sums[BATCH_VECTORS];
  for (int v = 0; v < BATCH_VECTORS; ++v) sums[v] = (frames)(0.0f);
  add_residual(row, p % CHANNELS, cap, slice_offsets, tail_offsets, residual_values,
               residual_lights, light, sums);
  write_frames(p, frame_stride, sums, output);
}

#endif

__kernel void dark_pixels(const uint runs_count, const uint frame_stride, __global const uint* runs,
                          __global const float* dark, __global const float* gains,
                          __global float* output) {
  const uint run = get_global_id(0);
  if (run >= runs_count) return;
  const uint first = runs[3 * run], pixels = runs[3 * run + 1];
  __global const float* gain = gains + runs[3 * run + 2] * CHANNELS;
  for (int b = 0; b < BATCH; ++b)
    for (int c = 0; c < CHANNELS; ++c) {
      const float value = dark[c * BATCH_PAD + b];
      __global float* out = output + b * frame_stride + first * CHANNELS + c;
      for (uint q = 0; q < pixels; ++q) out[q * CHANNELS] = gain[q * CHANNELS + c] * value;
    }
}
