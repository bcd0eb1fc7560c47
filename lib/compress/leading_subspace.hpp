// The leading right singular vectors of a row block X (n rows x m lights) at a cost linear in
// n x m: the small Gram matrix when one side of X is short (n x n when n < m, m x m when m is
// small), otherwise block subspace iteration on X^T X with a Rayleigh-Ritz step. Seeding, the L2
// rounds, the size rules, clustered PCA and the refit all find their subspaces here, so none of
// them pays the m x m Gram matrix and its O(m^3) eigenvectors at 1000+ lights.
#pragma once

#include <Eigen/Core>
#include <relume/field.hpp>

namespace relume {

// What orthonormalise_columns puts in place of a column (nearly) dependent on the earlier ones.
enum class DependentColumn { zero, unit_vector };

// Orthonormalises V's columns in place by modified Gram-Schmidt (twice, for stability); a column
// that is (nearly) in the span of the earlier ones becomes zero, or a unit vector that is not.
void orthonormalise_columns(Eigen::MatrixXd& V, DependentColumn dependent);

// How to find the subspace: `automatic` picks the cheaper of the two by a flop estimate.
enum class SubspaceMethod { automatic, gram, subspace_iteration };

// `terms` orthonormal rows (terms x m) spanning the best rank-`terms` least-squares subspace of
// X's rows, strongest first. Directions past X's rank are completed with other orthonormal
// vectors, so the result always has `terms` orthonormal rows (terms <= m). `warm_start` (terms x m,
// row-major), when given, is a guess of the subspace that the iteration starts from: the same
// answer in fewer iterations when the guess is close (the previous round's subspace).
Eigen::MatrixXd leading_right_singular_vectors(const RowMatrixF& X, int terms,
                                               SubspaceMethod method = SubspaceMethod::automatic,
                                               const float* warm_start = nullptr);

}  // namespace relume
