// Implementation of storing decoded light image rows into a field (see light_image_rows.hpp).
#include "field/light_image_rows.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <string>

#include "field/field_folder_writer.hpp"

namespace relume {

int field_channels(int image_channels) { return image_channels >= 3 ? 3 : 1; }

void check_same_shape(const ImageRowReader& image, const ImageRowReader& first) {
  if (image.width() != first.width() || image.height() != first.height())
    throw Error("image " + image.path().string() + " is " + std::to_string(image.width()) + "x" +
                std::to_string(image.height()) + " but " + first.path().string() + " is " +
                std::to_string(first.width()) + "x" + std::to_string(first.height()));
  if (image.channels() != first.channels())
    throw Error("image " + image.path().string() + " has " + std::to_string(image.channels()) +
                " channels but " + first.path().string() + " has " +
                std::to_string(first.channels()));
}

void store_light_rows(ReflectanceField& field, int light, const float* pixels, int image_channels,
                      int first_row, const std::filesystem::path& path) {
  auto where = [&](std::int64_t p, int c) {
    return " at pixel (" + std::to_string(p % field.width) + ", " +
           std::to_string(first_row + p / field.width) + ") channel " + std::to_string(c);
  };
  float scale[3];
  for (int c = 0; c < field.channels; ++c)
    scale[c] = 1.0f / channel_intensity(field.intensities, field.channels, light, c);
  for (std::int64_t p = 0; p < field.pixels(); ++p) {
    for (int c = 0; c < image_channels; ++c)
      if (!std::isfinite(pixels[p * image_channels + c]))
        throw Error("image " + path.string() + " has a non-finite value (" +
                    std::to_string(pixels[p * image_channels + c]) + ")" + where(p, c));
    for (int c = 0; c < field.channels; ++c) {
      const float value = pixels[p * image_channels + c] * scale[c];
      if (!std::isfinite(value))
        throw Error("image " + path.string() + " divided by its light intensity " +
                    std::to_string(channel_intensity(field.intensities, field.channels, light, c)) +
                    " overflows float32" + where(p, c));
      field.values(p * field.channels + c, light) = value;
    }
  }
}

float integer_noise_floor(int source_bits, EightBitEncoding encoding, const LightRgb& intensities) {
  if (source_bits <= 0) return 0.0f;
  double step = 1.0 / (std::ldexp(1.0, source_bits) - 1.0);
  // Decoded sRGB: the finest step is at black, where the curve's slope is 1 / 12.92.
  if (source_bits == 8 && encoding == EightBitEncoding::srgb) step /= 12.92;
  return float(step / double(intensities.mean()));
}

}  // namespace relume
