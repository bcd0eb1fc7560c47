// 2x2 box downsampling of reflectance fields (see downsample.hpp).
#include "field/downsample.hpp"

#include <relume/error.hpp>

namespace relume {

ReflectanceField downsample_field(const ReflectanceField& field) {
  if (field.width < 2 || field.height < 2)
    throw Error("cannot downsample a " + std::to_string(field.width) + "x" +
                std::to_string(field.height) + " field: it needs at least 2x2 pixels");
  ReflectanceField half;
  half.width = field.width / 2;
  half.height = field.height / 2;
  half.channels = field.channels;
  half.values.resize(half.pixels() * half.channels, field.lights());
  half.mask.assign(half.pixels(), 0);
  half.directions = field.directions;
  half.intensities = field.intensities;
  half.image_names = field.image_names;
  for (int y = 0; y < half.height; ++y) {
    for (int x = 0; x < half.width; ++x) {
      for (int c = 0; c < field.channels; ++c) {
        auto out = half.values.row(half.function_index(x, y, c));
        out = 0.25f * (field.values.row(field.function_index(2 * x, 2 * y, c)) +
                       field.values.row(field.function_index(2 * x + 1, 2 * y, c)) +
                       field.values.row(field.function_index(2 * x, 2 * y + 1, c)) +
                       field.values.row(field.function_index(2 * x + 1, 2 * y + 1, c)));
      }
      const auto inside = [&](int dx, int dy) {
        return field.mask[std::size_t(2 * y + dy) * field.width + 2 * x + dx] != 0;
      };
      half.mask[std::size_t(y) * half.width + x] =
          inside(0, 0) || inside(1, 0) || inside(0, 1) || inside(1, 1);
    }
  }
  return half;
}

ReflectanceField downsample_field(const ReflectanceField& field, int levels) {
  ReflectanceField result = field;
  for (int level = 0; level < levels; ++level) result = downsample_field(result);
  return result;
}

}  // namespace relume
