// Reference relighting of an uncompressed reflectance field: out[p] = sum_i R[p,i] * I[i, c(p)],
// accumulated in double. The ground truth that the compressed CPU and OpenCL paths are tested
// against.
#pragma once

#include "image/image.hpp"
#include "field/reflectance_field.hpp"

namespace relume {

// `light_vector` has one RGB row per light; a grey field uses the mean of each row.
Image relight_field(const ReflectanceField& field, const LightRgb& light_vector,
                    unsigned threads = 0);

}  // namespace relume
