// Implementation of field folders written from strips of scanlines.
#include "field/field_folder_writer.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <memory>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "field/light_file.hpp"
#include "image/scanline_writer.hpp"

namespace relume {
namespace fs = std::filesystem;
namespace {

// 001.exr ... with at least three digits.
std::vector<std::string> image_names(int lights) {
  const int digits = std::max(3, static_cast<int>(std::to_string(lights).size()));
  std::vector<std::string> names(lights);
  for (int i = 0; i < lights; ++i) {
    const std::string number = std::to_string(i + 1);
    names[i] = std::string(digits - number.size(), '0') + number + ".exr";
  }
  return names;
}

// How many images may be open at once: half the files this process may open, at least one.
int open_images_allowed() {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 1 << 16;
  return int(std::max<rlim_t>(1, std::min<rlim_t>(limit.rlim_cur / 2, 1 << 16)));
}

}  // namespace

void fill_strip_from(const ReflectanceField& field, int field_first_row, int first_row, int rows,
                     int first_light, int lights, float* values) {
  const std::int64_t row_functions = std::int64_t(field.width) * field.channels;
  const std::int64_t first = std::int64_t(first_row - field_first_row) * row_functions;
  for (int l = 0; l < lights; ++l)
    for (std::int64_t v = 0; v < rows * row_functions; ++v)
      *values++ = field.values(first + v, first_light + l);
}

float channel_intensity(const LightRgb& intensities, int channels, int light, int channel) {
  return channels == 1 ? intensities.row(light).mean() : intensities(light, channel);
}

void write_field_folder_in_strips(const fs::path& folder, const FieldFolderLayout& layout,
                                  const FieldStripFill& fill, const StripLimits& limits) {
  if (layout.channels != 1 && layout.channels != 3)
    throw Error("cannot write a field folder of " + std::to_string(layout.channels) +
                " channels: its light intensities are RGB, for 1 or 3 channels");
  fs::create_directories(folder);
  const int lights = int(layout.directions.rows());
  const std::vector<std::string> names = image_names(lights);
  const std::size_t row_values = std::size_t(layout.width) * layout.channels;
  const int group = std::max(
      1, std::min(lights, limits.open_images > 0 ? limits.open_images : open_images_allowed()));
  for (int first_light = 0; first_light < lights; first_light += group) {
    const int count = std::min(group, lights - first_light);
    const int strip_rows = int(std::clamp<std::size_t>(
        limits.strip_bytes / std::max<std::size_t>(1, row_values * count * sizeof(float)), 1,
        std::size_t(std::max(1, layout.height))));
    std::vector<std::unique_ptr<ScanlineWriter>> writers(count);
    for (int l = 0; l < count; ++l)
      writers[l] = std::make_unique<ScanlineWriter>(folder / names[first_light + l], layout.width,
                                                    layout.height, layout.channels);
    std::vector<float> values(std::size_t(count) * strip_rows * row_values);
    for (int first_row = 0; first_row < layout.height; first_row += strip_rows) {
      throw_if_interrupted();
      const int rows = std::min(strip_rows, layout.height - first_row);
      fill(first_row, rows, first_light, count, values.data());
      parallel_for(std::size_t(count), 0, [&](std::size_t l, unsigned) {
        float* image = values.data() + l * rows * row_values;
        std::vector<float> intensity(layout.channels);
        for (int c = 0; c < layout.channels; ++c)
          intensity[c] =
              channel_intensity(layout.intensities, layout.channels, first_light + int(l), c);
        for (std::size_t v = 0; v < rows * row_values; ++v)
          image[v] *= intensity[v % layout.channels];
        writers[l]->write_rows(first_row, rows, image);
      });
    }
    for (auto& writer : writers) writer->close();
  }
  write_rgb_rows(folder / "light_directions.txt", layout.directions, "");
  write_rgb_rows(folder / "light_intensities.txt", layout.intensities, "");
  Image mask(layout.width, layout.height, 1);
  for (std::size_t p = 0; p < layout.mask.size(); ++p)
    mask.pixels[p] = layout.mask[p] ? 1.0f : 0.0f;
  write_image(folder / "mask.png", mask);
  // The index goes last, so an interrupted write leaves no filenames.txt behind it.
  std::string index;
  for (const auto& name : names) index += name + "\n";
  write_file_atomically(folder / "filenames.txt", index);
}

}  // namespace relume
