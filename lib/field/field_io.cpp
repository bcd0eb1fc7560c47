// Loading reflectance fields from DiLiGenT-style folders and RTI .lp files; writing field folders.
#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "field/field_folder_writer.hpp"
#include "field/field_source.hpp"
#include "field/input_encoding.hpp"
#include "field/light_file.hpp"
#include "field/mask_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

int field_channels(int image_channels) { return image_channels >= 3 ? 3 : 1; }

void check_finite(const Image& image, const fs::path& path) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (std::isfinite(image.pixels[i])) continue;
    const std::size_t pixel = i / image.channels;
    throw Error("image " + path.string() + " has a non-finite value (" +
                std::to_string(image.pixels[i]) + ") at pixel (" +
                std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) +
                ") channel " + std::to_string(i % image.channels));
  }
}

}  // namespace

ReflectanceField load_field(const fs::path& path, const FieldLoadOptions& options) {
  const FieldSource source = describe_field(path);
  if (options.use_mask && !options.mask_file.empty() && !fs::exists(options.mask_file))
    throw Error("mask not found: " + options.mask_file.string());

  ImageReadOptions read;
  read.eight_bit = decide_input_encoding(source, options.image.eight_bit).encoding;
  const Image first = read_image(source.images.front(), read);
  ReflectanceField field;
  field.width = first.width;
  field.height = first.height;
  field.channels = field_channels(first.channels);
  const int lights = static_cast<int>(source.images.size());
  check_memory_need(std::uint64_t(field.pixels()) * std::uint64_t(field.channels) *
                        std::uint64_t(lights) * sizeof(float),
                    "the field " + path.string() + " (" + std::to_string(field.width) + "x" +
                        std::to_string(field.height) + ", " + std::to_string(field.channels) +
                        " channels, " + std::to_string(lights) + " lights, float32)");
  field.values.resize(field.pixels() * field.channels, lights);
  field.directions = source.directions;
  field.intensities = source.intensities.rows() ? source.intensities : LightRgb::Ones(lights, 3);
  for (const auto& image : source.images) field.image_names.push_back(image.filename().string());

  parallel_for(source.images.size(), options.threads, [&](std::size_t i, unsigned) {
    const Image image = i == 0 ? first : read_image(source.images[i], read);
    if (image.width != field.width || image.height != field.height)
      throw Error("image " + source.images[i].string() + " is " + std::to_string(image.width) +
                  "x" + std::to_string(image.height) + " but " + source.images[0].string() +
                  " is " + std::to_string(field.width) + "x" + std::to_string(field.height));
    if (image.channels != first.channels)
      throw Error("image " + source.images[i].string() + " has " + std::to_string(image.channels) +
                  " channels but " + source.images[0].string() + " has " +
                  std::to_string(first.channels));
    check_finite(image, source.images[i]);
    float scale[3];
    for (int c = 0; c < field.channels; ++c)
      scale[c] = 1.0f / channel_intensity(field.intensities, field.channels, int(i), c);
    for (std::int64_t p = 0; p < field.pixels(); ++p)
      for (int c = 0; c < field.channels; ++c) {
        const float value = image.pixels[p * image.channels + c] * scale[c];
        if (!std::isfinite(value))
          throw Error(
              "image " + source.images[i].string() + " divided by its light intensity " +
              std::to_string(channel_intensity(field.intensities, field.channels, int(i), c)) +
              " overflows float32 at pixel (" + std::to_string(p % field.width) + ", " +
              std::to_string(p / field.width) + ") channel " + std::to_string(c));
        field.values(p * field.channels + c, i) = value;
      }
    if (options.image_loaded) options.image_loaded();
  });

  const fs::path mask = options.mask_file.empty() ? source.mask : options.mask_file;
  field.mask = mask.empty() || !options.use_mask ? std::vector<std::uint8_t>(field.pixels(), 1)
                                                 : read_mask(mask, field.width, field.height);
  if (first.source_bits > 0) {
    double step = 1.0 / (std::ldexp(1.0, first.source_bits) - 1.0);
    // Decoded sRGB: the finest step is at black, where the curve's slope is 1 / 12.92.
    if (first.source_bits == 8 && read.eight_bit == EightBitEncoding::srgb) step /= 12.92;
    field.noise_floor = float(step / double(field.intensities.mean()));
  }
  return field;
}

void write_field_folder(const fs::path& folder, const ReflectanceField& field) {
  const FieldFolderLayout layout{field.width,      field.height,      field.channels,
                                 field.directions, field.intensities, field.mask};
  const std::int64_t row_functions = std::int64_t(field.width) * field.channels;
  write_field_folder_in_strips(
      folder, layout, [&](int first_row, int rows, int first_light, int lights, float* values) {
        for (int l = 0; l < lights; ++l)
          for (std::int64_t v = 0; v < rows * row_functions; ++v)
            *values++ = field.values(first_row * row_functions + v, first_light + l);
      });
}

}  // namespace relume
