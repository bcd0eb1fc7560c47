// Fitting cluster bases F^k: the least-squares subspace of a set of rows (used by seeding and the
// L2 rounds), an orthonormal basis of any F^k (for the cheap L2 projection error that preselects
// candidate clusters), and the F-step of the L1 factorization (paper section 3.3: every light's
// column of F^k fitted to the cluster's rows with W fixed, by IRLS warm-started at the current F).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "compress/cluster_function_fit.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

// The `terms` leading right singular vectors of the rows `members` of `rows` (t x m, row-major,
// orthonormal rows), at a cost linear in members x lights (leading_subspace.hpp); with `center`
// (m values) those of the rows minus `center` (the principal components about a mean). With fewer
// members than terms the missing directions are filled with other orthonormal vectors.
// `warm_start` (t x m) is a guess that speeds it up (see leading_right_singular_vectors).
std::vector<float> least_squares_subspace(const WorkingRows& rows,
                                          const std::vector<std::uint32_t>& members, int terms,
                                          const float* center = nullptr,
                                          const float* warm_start = nullptr);

// An m x t matrix whose columns are an orthonormal basis of the span of F's rows (zero columns
// where F is rank-deficient).
Eigen::MatrixXf orthonormal_columns(const float* basis, int terms, int lights);

// The F-step of one cluster (paper section 3.3) by IRLS, its rows summed one by one, so that they
// may come in blocks (a streamed pass over a field larger than memory). Each round sums, for
// every light i, sum_p v_pi W[p,:]^T W[p,:] and sum_p v_pi rows[p,i] W[p,:] with the IRLS weight
// v_pi = 1 / max(|e_pi|, epsilon) of the row's residual e under the current basis, and the
// light's L1 residual; ending it keeps every light's best basis column so far and solves the
// next. A last round without solving measures the final basis.
class BasisIrlsFit {
 public:
  BasisIrlsFit(int terms, int lights, float epsilon);
  void start_round();
  // Adds row x (lights values, unit norm) with weights w (terms) under `basis` (t x m); with
  // objective_only (the last round), only its per-light L1 residual.
  void add(const float* x, const float* w, const float* basis, bool objective_only = false);
  // Keeps each light's column of `basis` if its L1 residual is the smallest yet; with `solve`,
  // then sets `basis` to the weighted least-squares solution of the round.
  void end_round(float* basis, bool solve);
  // The best columns into `basis`, each basis row scaled to unit L2 norm; returns their L1
  // residual.
  double finish(float* basis) const;

  // The round's sums, one array (to add up the sums of rows held by other processes).
  std::vector<double>& sums() { return sums_; }

 private:
  int terms_, lights_;
  float epsilon_;
  std::size_t rhs_offset_, objective_offset_;
  // Per light: the Gram's pairs j >= l, then the right-hand side's terms, then the L1 residual.
  std::vector<double> sums_;
  std::vector<double> best_objective_;
  std::vector<float> best_;
  std::vector<float> residual_;
  std::vector<double> inverse_;
};

// F-step for one cluster (BasisIrlsFit over its members): for every light i,
// min_f sum_p |rows[p,i] - W[p,:] f| over the members, by `settings.iterations` IRLS steps from the
// current basis (updated in place). Each basis row is then scaled to unit L2 norm (W is refitted
// afterwards by the caller). Returns the L1 objective sum_p ||rows[p,:] - W[p,:] F||_1 with the new
// F.
double fit_cluster_basis_l1(const WorkingRows& rows, const std::vector<std::uint32_t>& members,
                            const RowMatrixF& weights, const IrlsSettings& settings, int terms,
                            float* basis);

}  // namespace relume
