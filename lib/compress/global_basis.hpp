// The field with one basis for every function: R[p,:] ~ W[p,:] F, F the `terms` leading right
// singular vectors of all stored functions (the best rank-`terms` least-squares fit), no
// clusters, no residual. Its weights are smooth images over the pixels, which is what camera-
// domain coding needs: the container codes them as JPEG 2000 planes (weight_plane_coding.hpp), and
// the rate targets (rate_control.hpp) weigh this model against the clustered ones.
#pragma once

#include <Eigen/Core>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>

namespace relume {

// The basis stored with 12-bit integers, one scale per basis function: its error is far below
// what the coded weights add, at a quarter of float32's bytes.
inline constexpr int global_basis_bits = 12;

// The stored functions of a field: every function inside the mask with some energy. Their
// leading right singular vectors, `terms` rows (terms <= lights), strongest first: a basis of k
// terms is the first k rows of a larger one.
Eigen::MatrixXd global_basis_directions(const ReflectanceField& field, int terms);

// The field as the first `terms` rows of `directions` (global_basis_directions) and each stored
// function's projection on them; W is float32 values until the container codes it.
CompressedField global_basis_field(const ReflectanceField& field,
                                   const Eigen::MatrixXd& directions, int terms);

}  // namespace relume
