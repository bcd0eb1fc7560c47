// Putting a light's decoded image rows into a field, shared by the whole-field loader
// (load_field) and the strip reader (field/field_strips.hpp): the shape checks against the first
// image, the division by the light's intensity with its NaN, Inf and overflow checks, and the
// noise floor that the images' integer depth implies.
#pragma once

#include <filesystem>
#include <relume/field.hpp>

#include "image/image_rows.hpp"

namespace relume {

// The field's channels for images of `image_channels` (RGB and RGBA: 3, else 1).
int field_channels(int image_channels);

// Throws Error naming both files when `image` differs from `first` in size or channels.
void check_same_shape(const ImageRowReader& image, const ImageRowReader& first);

// Stores light `light`'s rows (rows x field.width x image_channels decoded values, the field's
// pixels being image rows first_row onwards) into `field`, divided by the light's intensity.
// Throws Error naming `path` and the pixel (x, first_row + y) of a NaN or Inf value or of an
// overflow by the division.
void store_light_rows(ReflectanceField& field, int light, const float* pixels, int image_channels,
                      int first_row, const std::filesystem::path& path);

// The field's noise floor for images of `source_bits` (0 for floats: none) decoded as `encoding`:
// one step of the integer code (at black for sRGB) over the mean light intensity.
float integer_noise_floor(int source_bits, EightBitEncoding encoding, const LightRgb& intensities);

}  // namespace relume
