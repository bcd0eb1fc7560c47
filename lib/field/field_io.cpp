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
#include "field/light_image_rows.hpp"
#include "field/mask_file.hpp"

namespace relume {
namespace fs = std::filesystem;

ReflectanceField load_field(const fs::path& path, const FieldLoadOptions& options) {
  const FieldSource source = describe_field(path);
  if (options.use_mask && !options.mask_file.empty() && !fs::exists(options.mask_file))
    throw Error("mask not found: " + options.mask_file.string());

  ImageReadOptions read;
  read.eight_bit = decide_input_encoding(source, options.image.eight_bit).encoding;
  const ImageRowReader first(source.images.front(), read);
  ReflectanceField field;
  field.width = first.width();
  field.height = first.height();
  field.channels = field_channels(first.channels());
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
    ImageRowReader image(source.images[i], read);
    check_same_shape(image, first);
    std::vector<float> pixels(std::size_t(field.pixels()) * image.channels());
    image.read_rows(0, image.height(), pixels.data());
    store_light_rows(field, int(i), pixels.data(), image.channels(), 0, source.images[i]);
    if (options.image_loaded) options.image_loaded();
  });

  const fs::path mask = options.mask_file.empty() ? source.mask : options.mask_file;
  field.mask = mask.empty() || !options.use_mask ? std::vector<std::uint8_t>(field.pixels(), 1)
                                                 : read_mask(mask, field.width, field.height);
  field.noise_floor = integer_noise_floor(first.source_bits(), read.eight_bit, field.intensities);
  return field;
}

void write_field_folder(const fs::path& folder, const ReflectanceField& field) {
  const FieldFolderLayout layout{field.width,      field.height,      field.channels,
                                 field.directions, field.intensities, field.mask};
  write_field_folder_in_strips(
      folder, layout, [&](int first_row, int rows, int first_light, int lights, float* values) {
        fill_strip_from(field, 0, first_row, rows, first_light, lights, values);
      });
}

}  // namespace relume
