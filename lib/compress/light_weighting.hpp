// Light weighting (issue 17): Eq. 16 weighs each function's lights by their share of its energy,
// so the lights that reach a scene only at grazing angles (a sun behind the object lights its
// rims) hold a thousandth of a front light's energy and their errors hardly count, though an
// environment concentrated on them shows those errors undiluted. With an exponent a > 0 the
// factorization fits R[p,i] / s_i instead of R, with s_i = (D_i / max D)^a, D_i the RMS of light
// i's image (at least 1e-3 max D): a = 1 makes every light's image count alike relative to its
// own energy, 0.5 halfway (in log scale). Exact: R ~ W (F S) + E S with S = diag(s), so F's
// columns and the residual entries are scaled back and the container and relighting are as for
// any field; only which fit and which residual entries are chosen changes.
#pragma once

#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// s_i for every light of `field` (over the functions inside its mask); throws Error for an
// exponent outside [0, 1]. Exponent 0: every s_i is 1.
std::vector<float> light_weighting_scales(const ReflectanceField& field, double exponent);

// The residual row just appended to `rows` (from entry `begin` on), chosen from a weighted row,
// back in field units: each value times its light's scale, re-sorted by |value| descending (ties
// by light index), as every stored row is.
void unweight_residual_row(ResidualRows& rows, std::size_t begin,
                           const std::vector<float>& light_scale);

}  // namespace relume
