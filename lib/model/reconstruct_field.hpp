// Reconstruction of a reflectance field from its compressed form, R~[p,:] = W[p,:] F^{c(p)} +
// E[p,:] (with the residual cut to its first `residual_cap` entries per row: the dynamic residual),
// and the paper's error measure (Eq. 16) between an original field and a compressed one.
#pragma once

#include <cstdint>

#include "model/compressed_field.hpp"
#include "field/reflectance_field.hpp"

namespace relume {

// residual_cap: entries of each residual row to keep (its largest ones, since rows are sorted by
// |value| descending); -1 keeps all. Anything below -1 is refused.
inline constexpr int all_residual_entries = -1;

// Stored row `row` of `field` in the basis the field is stored in (before any inverse transform):
// out[i] = sum_j W[row,j] F^{c(row)}[j][i] + sum_{k < cap} E values at their lights. Accumulates
// in double. `out` holds field.lights floats. Throws Error for a row out of range; the field itself
// is trusted (validated fields only).
void reconstruct_stored_row(const CompressedField& field, std::size_t row, int residual_cap,
                            float* out);

// The whole field in the original (light) basis: stored rows reconstructed and, for a Haar-stored
// field, transformed back; functions that are not stored are zero. Mask, directions and
// intensities are copied; image_names are left empty (write_field_folder names the images).
// Throws Error for an inconsistent field (validate_compressed_field) or a cap below -1.
ReflectanceField reconstruct_field(const CompressedField& field,
                                   int residual_cap = all_residual_entries);

// Paper Eq. 16: err = (1/n) sum_p ( sum_i (R[p,i] - R~[p,i])^2 / sum_i R[p,i]^2 ).
// Functions whose original energy sum_i R[p,i]^2 is zero have no defined relative error: they are
// left out of the average (n counts only the others) and counted in zero_energy_skipped.
struct RelativeError {
  double mean = 0;                       // the average above; 0 when nothing was averaged
  std::int64_t functions_averaged = 0;   // n
  std::int64_t zero_energy_skipped = 0;  // functions left out for having zero energy
};

// masked_only: average only over functions whose pixel is inside the compressed field's mask.
// Throws Error unless `original` has the compressed field's size, channels and lights, or for an
// inconsistent compressed field or a cap below -1. Accumulates in double, in fixed blocks, so
// the result does not depend on `threads` (0 = all cores).
RelativeError relative_error(const ReflectanceField& original, const CompressedField& compressed,
                             bool masked_only, int residual_cap = all_residual_entries,
                             unsigned threads = 0);

// Eq. 16 of `approximation` against `reference`, two compressions of the same field (or one with
// itself at a shorter residual), over the functions `reference` stores (each with its full
// residual; functions `approximation` does not store count as zero), compared in the light basis.
// `approximation_cap`: residual entries per row of `approximation` (all_residual_entries: all).
RelativeError relative_error(const CompressedField& reference, const CompressedField& approximation,
                             int approximation_cap = all_residual_entries, unsigned threads = 0);

}  // namespace relume
