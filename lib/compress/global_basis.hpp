// The field with one basis for every function: R[p,:] ~ W[p,:] F, F the `terms` leading right
// singular vectors of all stored functions (the best rank-`terms` least-squares fit), no
// clusters, no residual. Its weights are smooth images over the pixels, which is what camera-
// domain coding needs: the container codes them as JPEG 2000 planes (weight_plane_coding.hpp), and
// the rate targets (rate_control.hpp) weigh this model against the clustered ones.
#pragma once

#include <Eigen/Core>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// The basis is stored as integers of at most 12 bits times one step per basis function. The
// steps are as coarse as keeps the basis's error (weighted by each term's weight energy) at this
// share of the error of truncating the basis, or of the sensor noise's energy over the stored
// values where that is larger (the coded weights' error is at least about the noise):
// negligible next to what the coded weights add, at about half the bytes of a fixed 12 bits
// (3.7 against 7.2 KB for 48 terms of 96 lights; 8.7 against 16.1 KB for all 96 terms of the
// 8-bit ball, where nothing is truncated).
inline constexpr int global_basis_bits = 12;
inline constexpr double basis_error_share = 0.01;

// The stored functions of a field: every function inside the mask with some energy. Their
// leading right singular vectors, `terms` rows (terms <= lights), strongest first: a basis of k
// terms is the first k rows of a larger one.
Eigen::MatrixXd global_basis_directions(const ReflectanceField& field, int terms);

// The field as the first `terms` rows of `directions` (global_basis_directions), quantized, and
// each stored function's projection on the unquantized rows (the basis's quantization error is
// the one budgeted above); W is float32 values until the container codes it. `threads`: 0 = one
// per core. `noise_sigma`: the noise's deviation per channel (noise_model.hpp); empty: none
// known, the basis budgeted by its truncation alone.
CompressedField global_basis_field(const ReflectanceField& field, const Eigen::MatrixXd& directions,
                                   int terms, unsigned threads = 0,
                                   const std::vector<float>& noise_sigma = {});

// `coded`'s basis (a global_basis_field whose W the container's coding has replaced by what its
// codestream decodes to) refitted to that W: F = argmin |X - W F|^2 over the stored functions X,
// the least-squares answer to the coding's error in W. Stored at the steps the weights were
// coded for (coarser only where a refit row outgrew its 12 bits), so its bytes stay about those
// the rate search planned.
void refit_global_basis(const ReflectanceField& field, CompressedField& coded,
                        unsigned threads = 0);

}  // namespace relume
