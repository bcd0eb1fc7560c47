// Reassignment of reflectance functions to clusters (paper Eq. 14), the OpenCL twin of
// lib/compress/cluster_assignment.cpp + lib/compress/cluster_function_fit.cpp: one work-item per row fits the row's
// TERMS weights against each of its candidate clusters by IRLS (least-squares start, then
// ITERATIONS reweighted solves with weights 1 / max(|e|, EPSILON)), scores each fit by its exact
// L1 residual and keeps the best and the runner-up.
//
//   rows:       row_count x LIGHTS, unit-norm rows
//   bases:      clusters x TERMS x LIGHTS (F^k row j at (k * TERMS + j) * LIGHTS)
//   candidates: row_count x WIDTH cluster ids, -1 ends a row's list
//   outputs:    best, second (-1 if none), objective, weights (row_count x TERMS)
//
// Each IRLS step is one pass over the lights in vectors of LIGHT_VECTOR (4, 8 or 16;
// the host picks the CPU's native float width, 4 on GPUs): it scores the
// current weights (residual e, its L1 sum) and, from the same e, sums the next solve's normal
// equations. No per-light array is kept, and the lights are read as vectors from contiguous rows.
// The small normal equations are solved in REAL (double where the device has fp64).

#ifndef TERMS
#define TERMS 4
#endif
#ifndef LIGHTS
#define LIGHTS 96
#endif
#ifndef WIDTH
#define WIDTH 4
#endif
#ifndef ITERATIONS
#define ITERATIONS 5
#endif
#ifndef EPSILON
#define EPSILON 1e-4f
#endif
#ifndef USE_DOUBLE
#define USE_DOUBLE 0
#endif
#ifndef LIGHT_VECTOR
#define LIGHT_VECTOR 8
#endif

#if USE_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double REAL;
#else
typedef float REAL;
#endif

#if LIGHT_VECTOR == 4
typedef float4 lights_t;
#define load_lights(offset, pointer) vload4(offset, pointer)
inline float lane_sum(const float4 four) { return four.x + four.y + four.z + four.w; }
#elif LIGHT_VECTOR == 8
typedef float8 lights_t;
#define load_lights(offset, pointer) vload8(offset, pointer)
inline float lane_sum(const float8 v) {
  const float4 four = v.lo + v.hi;
  return four.x + four.y + four.z + four.w;
}
#elif LIGHT_VECTOR == 16
typedef float16 lights_t;
#define load_lights(offset, pointer) vload16(offset, pointer)
inline float lane_sum(const float16 v) {
  const float8 eight = v.lo + v.hi;
  const float4 four = eight.lo + eight.hi;
  return four.x + four.y + four.z + four.w;
}
#else
#error "LIGHT_VECTOR must be 4, 8 or 16"
#endif

#define FULL_VECTORS (LIGHTS / LIGHT_VECTOR)
#define TAIL_LIGHTS (LIGHTS % LIGHT_VECTOR)
#define PAIRS (TERMS * (TERMS + 1) / 2)  // lower triangle of the normal matrix

// The last, partial vector of lights, zero beyond LIGHTS: a zero light adds nothing to the L1
// sum (e = 0) nor to the normal equations (d * 0 * 0).
inline lights_t load_tail(__global const float* pointer) {
  float lanes[LIGHT_VECTOR];
  for (int i = 0; i < LIGHT_VECTOR; ++i)
    lanes[i] = i < TAIL_LIGHTS ? pointer[FULL_VECTORS * LIGHT_VECTOR + i] : 0.0f;
  return load_lights(0, lanes);
}

// What a pass over the lights does (see fit_pass).
#define PASS_START 0     // sum the least-squares normal equations (d = 1)
#define PASS_REWEIGHT 1  // score w and sum the normal equations with d = 1 / max(|e|, EPSILON)
#define PASS_SCORE 2     // score w only

// One vector of lights of a pass: adds |e| to l1 and d f_j f_l, d f_j x to the normal equations.
inline void pass_step(const lights_t* f, const lights_t x, const float* w, const int mode,
                      lights_t* l1, lights_t* g, lights_t* b) {
  lights_t d = (lights_t)(1.0f);
  if (mode != PASS_START) {
    lights_t e = x;
    for (int j = 0; j < TERMS; ++j) e -= w[j] * f[j];
    const lights_t magnitude = fabs(e);
    *l1 += magnitude;
    if (mode == PASS_SCORE) return;
    d = 1.0f / fmax(magnitude, EPSILON);
  }
  int pair = 0;
  for (int j = 0; j < TERMS; ++j) {
    const lights_t weighted = d * f[j];
    b[j] += weighted * x;
    for (int l = 0; l <= j; ++l) g[pair++] += weighted * f[l];
  }
}

// One pass over all lights in `mode` (PASS_*): returns the L1 residual of the weights w (0 for
// PASS_START) and, unless scoring only, leaves the normal equations in gram (TERMS x TERMS, full)
// and rhs (TERMS).
float fit_pass(__global const float* f, __global const float* x, const float* w, const int mode,
               REAL* gram, REAL* rhs) {
  lights_t l1 = (lights_t)(0.0f), g[PAIRS], b[TERMS];
  for (int i = 0; i < PAIRS; ++i) g[i] = (lights_t)(0.0f);
  for (int j = 0; j < TERMS; ++j) b[j] = (lights_t)(0.0f);
  lights_t fv[TERMS];
  for (int v = 0; v < FULL_VECTORS; ++v) {
    for (int j = 0; j < TERMS; ++j) fv[j] = load_lights(v, f + j * LIGHTS);
    pass_step(fv, load_lights(v, x), w, mode, &l1, g, b);
  }
#if TAIL_LIGHTS > 0
  for (int j = 0; j < TERMS; ++j) fv[j] = load_tail(f + j * LIGHTS);
  pass_step(fv, load_tail(x), w, mode, &l1, g, b);
#endif
  if (mode == PASS_SCORE) return lane_sum(l1);
  int pair = 0;
  for (int j = 0; j < TERMS; ++j) {
    rhs[j] = lane_sum(b[j]);
    for (int l = 0; l <= j; ++l, ++pair) gram[j * TERMS + l] = gram[l * TERMS + j] = lane_sum(g[pair]);
  }
  return lane_sum(l1);
}

// Solves G x = b (TERMS x TERMS, symmetric positive semi-definite) by Cholesky with a small ridge;
// directions without support get x = 0. G and b are overwritten; x is left in b.
void solve_small_spd(REAL* g, REAL* b) {
  REAL trace = 0;
  for (int j = 0; j < TERMS; ++j) trace += g[j * TERMS + j];
  const REAL ridge = (REAL)1e-10 * trace + (REAL)1e-30;
  for (int j = 0; j < TERMS; ++j) g[j * TERMS + j] += ridge;
  for (int j = 0; j < TERMS; ++j) {
    REAL diagonal = g[j * TERMS + j];
    for (int k = 0; k < j; ++k) diagonal -= g[j * TERMS + k] * g[j * TERMS + k];
    if (!(diagonal > ridge * (REAL)1e-3)) {
      for (int i = j; i < TERMS; ++i) g[i * TERMS + j] = 0;
      g[j * TERMS + j] = 1;
      continue;
    }
    const REAL root = sqrt(diagonal);
    g[j * TERMS + j] = root;
    for (int i = j + 1; i < TERMS; ++i) {
      REAL value = g[i * TERMS + j];
      for (int k = 0; k < j; ++k) value -= g[i * TERMS + k] * g[j * TERMS + k];
      g[i * TERMS + j] = value / root;
    }
  }
  for (int j = 0; j < TERMS; ++j) {
    REAL value = b[j];
    for (int k = 0; k < j; ++k) value -= g[j * TERMS + k] * b[k];
    b[j] = value / g[j * TERMS + j];
  }
  for (int j = TERMS - 1; j >= 0; --j) {
    REAL value = b[j];
    for (int k = j + 1; k < TERMS; ++k) value -= g[k * TERMS + j] * b[k];
    b[j] = value / g[j * TERMS + j];
  }
}

// The IRLS fit of row x against basis f: the lowest L1 residual seen, its weights in `fitted`.
float fit_row(__global const float* f, __global const float* x, float* fitted) {
  REAL gram[TERMS * TERMS], rhs[TERMS];
  float current[TERMS];
  fit_pass(f, x, current, PASS_START, gram, rhs);
  float best = INFINITY;
  for (int step = 0; step <= ITERATIONS; ++step) {
    solve_small_spd(gram, rhs);
    for (int j = 0; j < TERMS; ++j) current[j] = (float)rhs[j];
    // Scores `current` and, unless it is the last solve, sets up the next one.
    const float objective =
        fit_pass(f, x, current, step < ITERATIONS ? PASS_REWEIGHT : PASS_SCORE, gram, rhs);
    if (objective < best) {
      best = objective;
      for (int j = 0; j < TERMS; ++j) fitted[j] = current[j];
    }
  }
  return best;
}

__kernel void assign_rows(__global const float* rows, __global const float* bases,
                          __global const int* candidates, const uint row_count,
                          __global int* best_out, __global int* second_out,
                          __global float* objective_out, __global float* weights_out) {
  const uint r = get_global_id(0);
  if (r >= row_count) return;
  __global const float* x = rows + (size_t)r * LIGHTS;
  float best = INFINITY, second = INFINITY;
  int best_k = -1, second_k = -1;
  float best_w[TERMS];
  for (int j = 0; j < TERMS; ++j) best_w[j] = 0.0f;
  for (int slot = 0; slot < WIDTH; ++slot) {
    const int k = candidates[(size_t)r * WIDTH + slot];
    if (k < 0) break;
    float fitted[TERMS];
    const float objective = fit_row(bases + (size_t)k * TERMS * LIGHTS, x, fitted);
    if (objective < best) {
      second = best;
      second_k = best_k;
      best = objective;
      best_k = k;
      for (int j = 0; j < TERMS; ++j) best_w[j] = fitted[j];
    } else if (objective < second) {
      second = objective;
      second_k = k;
    }
  }
  best_out[r] = best_k;
  second_out[r] = second_k;
  objective_out[r] = best_k < 0 ? 0.0f : best;
  for (int j = 0; j < TERMS; ++j) weights_out[(size_t)r * TERMS + j] = best_w[j];
}
