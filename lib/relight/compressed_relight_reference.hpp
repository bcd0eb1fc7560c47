// The steps of the CPU reference relighter (relume/relight.hpp) that the OpenCL relighter and the
// benchmarks share: the field check, the light vector in the field's basis (see
// light_in_field_basis) and the per-cluster products v = F^k . I.
#pragma once

#include <relume/relight.hpp>
#include <vector>

namespace relume {

// Throws Error naming the first inconsistency that would make relighting read out of bounds or
// produce garbage: validate_compressed_field (model/compressed_field_checks.hpp) plus a channel
// count of 1 or 3.
void check_relightable(const CompressedField& field);

// The light vector as the field's rows see it: lights x channels (a grey field uses the mean of
// each RGB row, as relight_field does), then transformed into the field's basis. Throws Error
// for a wrong row count or NaN/Inf entries.
RowMatrixF light_in_field_basis(const CompressedField& field, const LightRgb& light);

// v[(k * terms + j) * channels + c] for a light vector already in the field's basis.
std::vector<double> cluster_light_products(const CompressedField& field,
                                           const RowMatrixF& basis_light);

// What every dark pixel's channel c relights to, dark[c] . I (empty without dark pixels).
std::vector<double> dark_light_products(const CompressedField& field,
                                        const RowMatrixF& basis_light);

}  // namespace relume
