// CPU reference relighting of a CompressedField, accumulated in double: the ground truth that the
// OpenCL kernels are tested against. For stored row s (function p, channel c = p % channels,
// cluster k):
//   v[k][j][c] = sum_i F^k[j][i] * I[i][c]
//   out[p]     = sum_j W[s][j] * v[k][j][c] + sum_{e < min(nnz_s, cap)} E[s][e] * I[light(e)][c]
// Functions that are not stored relight to 0. I is the light vector in the field's basis (see
// light_in_field_basis).
#pragma once

#include <limits>
#include <vector>

#include "model/compressed_field.hpp"
#include "image/image.hpp"

namespace relume {

// A residual cap that keeps every stored residual entry.
inline constexpr int full_residual = std::numeric_limits<int>::max();

// Which parts of the sum to evaluate: the whole relit image, or only the residual term E . I
// (the residual SpMV on its own).
enum class RelightTerms { all, residual_only };

// Throws Error naming the first inconsistency that would make relighting read out of bounds or
// produce garbage: validate_compressed_field (container.hpp) plus a channel count of 1 or 3.
void check_relightable(const CompressedField& field);

// The light vector as the field's rows see it: lights x channels (a grey field uses the mean of
// each RGB row, as relight_field does), then transformed into the field's basis. Throws Error
// for a wrong row count or NaN/Inf entries.
RowMatrixF light_in_field_basis(const CompressedField& field, const LightRgb& light);

// v[(k * terms + j) * channels + c] for a light vector already in the field's basis.
std::vector<double> cluster_light_products(const CompressedField& field,
                                           const RowMatrixF& basis_light);

// The reference relighter of one field: checks the field once (check_relightable), then relights
// it for any number of light vectors. Keeps a reference to the field, which must outlive it.
class CompressedRelightReference {
 public:
  explicit CompressedRelightReference(const CompressedField& field);

  // Relit image (width x height x channels); at most residual_cap >= 0 entries per row are used.
  Image relight(const LightRgb& light, int residual_cap = full_residual,
                RelightTerms terms = RelightTerms::all, unsigned threads = 0) const;

 private:
  const CompressedField& field_;
};

// One-off form of CompressedRelightReference(field).relight(...).
Image relight_compressed_reference(const CompressedField& field, const LightRgb& light,
                                   int residual_cap = full_residual,
                                   RelightTerms terms = RelightTerms::all, unsigned threads = 0);

}  // namespace relume
