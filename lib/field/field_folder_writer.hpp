// Field folders written from strips of scanlines (the layout of write_field_folder in
// relume/field.hpp: one EXR per light, 001.exr ..., light_directions.txt, light_intensities.txt,
// mask.png, and filenames.txt last), so that no field need be whole in memory: write_field_folder
// copies its strips from the field it holds, `relume decompress` reconstructs them from a
// container one strip at a time.
#pragma once

#include <filesystem>
#include <functional>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// What a field folder holds besides its images' values.
struct FieldFolderLayout {
  int width = 0, height = 0, channels = 0;
  LightDirections directions;      // lights x 3
  LightRgb intensities;            // lights x 3, the values are written multiplied by them
  std::vector<std::uint8_t> mask;  // width * height, non-zero inside
};

// The intensity a channel of light i is divided by on load (multiplied by on write): its own for
// RGB, the mean of the three for grey fields.
float channel_intensity(const LightRgb& intensities, int channels, int light, int channel);

// Fills the field's values (field units) of pixel rows [first_row, first_row + rows) under lights
// [first_light, first_light + lights), light-major:
// values[((l * rows + y) * width + x) * channels + c].
using FieldStripFill =
    std::function<void(int first_row, int rows, int first_light, int lights, float* values)>;

// The FieldStripFill of pixel rows [first_row, first_row + rows) and lights [first_light,
// first_light + lights) from `field`, which holds the field's pixel rows from `field_first_row`
// (0 for a whole field, first_row for a strip rendered for the purpose).
void fill_strip_from(const ReflectanceField& field, int field_first_row, int first_row, int rows,
                     int first_light, int lights, float* values);

// How much is held at once: strips of at most `strip_bytes` of values (at least one row of
// pixels), at most `open_images` images open (0: half the files the process may open); more
// lights take several passes over the strips.
struct StripLimits {
  std::size_t strip_bytes = std::size_t(64) << 20;
  int open_images = 0;
};

// Writes the folder, the images strip by strip. Throws Error naming the file at fault,
// Interrupted between strips when asked to stop.
void write_field_folder_in_strips(const std::filesystem::path& folder,
                                  const FieldFolderLayout& layout, const FieldStripFill& fill,
                                  const StripLimits& limits = {});

}  // namespace relume
