// The inner solve of clustered factorization: the t weights of one reflectance function against
// one cluster basis F (t x m) in the L1 sense (paper Eq. 14), by iteratively reweighted least
// squares started from the least-squares fit. IRLS is approximate: the objective returned is the
// exact L1 norm of the best iterate, so callers compare clusters by true residuals. The OpenCL
// kernel kernels/assign.cl runs the same iteration; this is its CPU reference.
#pragma once

#include <vector>

namespace relume {

inline constexpr int max_cluster_terms = 16;

struct IrlsSettings {
  int iterations = 5;     // reweighted solves after the least-squares start
  float epsilon = 1e-4f;  // smallest |residual| in the weights 1 / max(|e|, epsilon), relative
                          // to the function's L2 norm
};

// Working memory of one thread (m floats of residual and t x m weighted basis values).
struct FunctionFitScratch {
  std::vector<float> residual, weighted_basis;
};

// min_w || row - w^T F ||_1 approximately; `basis` is t x m row-major (row j = basis function j),
// `norm` the L2 norm of `row` (scales epsilon). Writes t weights and returns the L1 objective.
float fit_function_l1(const float* basis, int terms, int lights, const float* row, float norm,
                      const IrlsSettings& settings, float* weights, FunctionFitScratch& scratch);

// Solves the symmetric positive semi-definite system G x = b (n <= max_cluster_terms, G row-major,
// both overwritten) by Cholesky with a small ridge relative to the trace; directions with no
// support get x = 0.
void solve_small_spd(double* gram, double* rhs, int n);

}  // namespace relume
