// Reassignment of reflectance functions to clusters (paper Eq. 14), the OpenCL twin of
// lib/cluster_assignment.cpp + lib/cluster_function_fit.cpp: one work-item per row fits the row's
// TERMS weights against each of its candidate clusters by IRLS (least-squares start, then
// ITERATIONS reweighted solves with weights 1 / max(|e|, EPSILON)), scores each fit by its exact
// L1 residual and keeps the best and the runner-up.
//
//   rows:       row_count x LIGHTS, unit-norm rows
//   bases:      clusters x TERMS x LIGHTS (F^k row j at (k * TERMS + j) * LIGHTS)
//   candidates: row_count x WIDTH cluster ids, -1 ends a row's list
//   outputs:    best, second (-1 if none), objective, weights (row_count x TERMS)
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

#if USE_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double REAL;
#else
typedef float REAL;
#endif

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

// w = argmin sum_i d_i (x_i - w . F_i)^2, with d_i = 1 when `unit` (the least-squares start).
void solve_weighted(__global const float* f, __global const float* x, const float* d, int unit,
                    float* w) {
  REAL g[TERMS * TERMS], b[TERMS];
  for (int j = 0; j < TERMS; ++j) {
    for (int l = 0; l <= j; ++l) {
      float sum = 0.0f;
      for (int i = 0; i < LIGHTS; ++i) {
        const float weighted = unit ? f[j * LIGHTS + i] : d[i] * f[j * LIGHTS + i];
        sum += weighted * f[l * LIGHTS + i];
      }
      g[j * TERMS + l] = g[l * TERMS + j] = sum;
    }
    float sum = 0.0f;
    for (int i = 0; i < LIGHTS; ++i) {
      const float weighted = unit ? f[j * LIGHTS + i] : d[i] * f[j * LIGHTS + i];
      sum += weighted * x[i];
    }
    b[j] = sum;
  }
  solve_small_spd(g, b);
  for (int j = 0; j < TERMS; ++j) w[j] = (float)b[j];
}

// e = x - w F; returns sum |e|.
float residual_l1(__global const float* f, __global const float* x, const float* w, float* e) {
  for (int i = 0; i < LIGHTS; ++i) e[i] = x[i];
  for (int j = 0; j < TERMS; ++j)
    for (int i = 0; i < LIGHTS; ++i) e[i] -= w[j] * f[j * LIGHTS + i];
  float sum = 0.0f;
  for (int i = 0; i < LIGHTS; ++i) sum += fabs(e[i]);
  return sum;
}

__kernel void assign_rows(__global const float* rows, __global const float* bases,
                          __global const int* candidates, const uint row_count,
                          __global int* best_out, __global int* second_out,
                          __global float* objective_out, __global float* weights_out) {
  const uint r = get_global_id(0);
  if (r >= row_count) return;
  __global const float* x = rows + (size_t)r * LIGHTS;
  float e[LIGHTS];
  float best = INFINITY, second = INFINITY;
  int best_k = -1, second_k = -1;
  float best_w[TERMS];
  for (int j = 0; j < TERMS; ++j) best_w[j] = 0.0f;
  for (int slot = 0; slot < WIDTH; ++slot) {
    const int k = candidates[(size_t)r * WIDTH + slot];
    if (k < 0) break;
    __global const float* f = bases + (size_t)k * TERMS * LIGHTS;
    float current[TERMS], fitted[TERMS];
    solve_weighted(f, x, e, 1, current);
    float objective = residual_l1(f, x, current, e);
    for (int j = 0; j < TERMS; ++j) fitted[j] = current[j];
    for (int iteration = 0; iteration < ITERATIONS; ++iteration) {
      for (int i = 0; i < LIGHTS; ++i) e[i] = 1.0f / fmax(fabs(e[i]), EPSILON);
      solve_weighted(f, x, e, 0, current);
      const float value = residual_l1(f, x, current, e);
      if (value < objective) {
        objective = value;
        for (int j = 0; j < TERMS; ++j) fitted[j] = current[j];
      }
    }
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
