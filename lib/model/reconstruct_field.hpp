// Reconstruction of one stored row of a compressed field, R~[p,:] = W[p,:] F^{c(p)} + E[p,:] (with
// the residual cut to its first `residual_cap` entries: the dynamic residual). The whole-field
// reconstruction and the error measure are declared in relume/compressed_field.hpp.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>

namespace relume {

// Stored row `row` of `field` in the basis the field is stored in (before any inverse transform):
// out[i] = sum_j W[row,j] F^{c(row)}[j][i] + sum_{k < cap} E values at their lights. Accumulates
// in double. `out` holds field.lights floats. Throws Error for a row out of range; the field itself
// is trusted (validated fields only).
void reconstruct_stored_row(const CompressedField& field, std::size_t row, int residual_cap,
                            float* out);

}  // namespace relume
