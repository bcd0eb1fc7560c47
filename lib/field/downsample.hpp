// Camera-space downsampling of a reflectance field for multi-resolution clustering: each output
// pixel is the 2x2 box average of its input pixels (an odd last row/column is dropped), and is
// inside the mask when any of its four input pixels is.
#pragma once

#include <relume/field.hpp>

namespace relume {

ReflectanceField downsample_field(const ReflectanceField& field);

// Applies downsample_field `levels` times (0 returns a copy).
ReflectanceField downsample_field(const ReflectanceField& field, int levels);

}  // namespace relume
