// Loading reflectance fields from disk and writing them back.
//
// A field folder (DiLiGenT layout) holds the light images, `filenames.txt` (one image name per
// light; without it, images are the numbered files 001.png ... in name order), 
// `light_directions.txt`, optional `light_intensities.txt` (each image is divided by its row, per
// channel) and optional `mask.png` (non-zero = inside). An RTI `.lp` file names its images itself.
// Images load in parallel; every image must have the same size and channel count, and NaN/Inf
// pixels are refused with the image and pixel named.
#pragma once

#include <filesystem>

#include "image/image_io.hpp"
#include "field/reflectance_field.hpp"

namespace relume {

struct FieldLoadOptions {
  ImageReadOptions image;
  unsigned threads = 0;  // 0 = all cores
};

// `path` is a field folder or an .lp file.
ReflectanceField load_field(const std::filesystem::path& path, const FieldLoadOptions& options = {});

// Writes a field folder that load_field reads back: one EXR per light (001.exr ...),
// filenames.txt, light_directions.txt, light_intensities.txt (the field's intensities; its values
// are written multiplied back by them, so the round trip is exact) and mask.png.
void write_field_folder(const std::filesystem::path& folder, const ReflectanceField& field);

}  // namespace relume
