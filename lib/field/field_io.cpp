// Loading reflectance fields from DiLiGenT-style folders and RTI .lp files; writing field folders.
#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "field/field_source.hpp"
#include "field/input_encoding.hpp"
#include "field/light_file.hpp"
#include "field/mask_file.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

int field_channels(int image_channels) { return image_channels >= 3 ? 3 : 1; }

// The intensity a channel of light i was divided by: its own for RGB, the mean for grey fields.
float channel_intensity(const ReflectanceField& field, int light, int channel) {
  return field.channels == 1 ? field.intensities.row(light).mean()
                             : field.intensities(light, channel);
}

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
    for (int c = 0; c < field.channels; ++c) scale[c] = 1.0f / channel_intensity(field, i, c);
    for (std::int64_t p = 0; p < field.pixels(); ++p)
      for (int c = 0; c < field.channels; ++c) {
        const float value = image.pixels[p * image.channels + c] * scale[c];
        if (!std::isfinite(value))
          throw Error("image " + source.images[i].string() + " divided by its light intensity " +
                      std::to_string(channel_intensity(field, int(i), c)) +
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
  fs::create_directories(folder);
  const int lights = field.lights();
  const int digits = std::max(3, static_cast<int>(std::to_string(lights).size()));
  std::vector<std::string> image_names(lights);
  for (int i = 0; i < lights; ++i) {
    const std::string number = std::to_string(i + 1);
    image_names[i] = std::string(digits - number.size(), '0') + number + ".exr";
  }
  parallel_for(lights, 0, [&](std::size_t i, unsigned) {
    Image image(field.width, field.height, field.channels);
    for (std::int64_t p = 0; p < field.pixels(); ++p)
      for (int c = 0; c < field.channels; ++c)
        image.pixels[p * field.channels + c] =
            field.values(p * field.channels + c, i) * channel_intensity(field, int(i), c);
    write_image(folder / image_names[i], image);
  });
  std::string names;
  for (const auto& name : image_names) names += name + "\n";
  write_rgb_rows(folder / "light_directions.txt", field.directions, "");
  write_rgb_rows(folder / "light_intensities.txt", field.intensities, "");
  Image mask(field.width, field.height, 1);
  for (std::size_t p = 0; p < field.mask.size(); ++p) mask.pixels[p] = field.mask[p] ? 1.0f : 0.0f;
  write_image(folder / "mask.png", mask);
  // The index goes last, so an interrupted write leaves no filenames.txt behind it.
  write_file_atomically(folder / "filenames.txt", names);
}

}  // namespace relume
