// Which files make up a reflectance field on disk: a DiLiGenT-style folder (filenames.txt or
// numbered images, light_directions.txt, optional light_intensities.txt and mask.png) or an RTI
// .lp file (or a folder holding exactly one). Only names and light files are read here; the
// images are loaded by load_field (relume/field.hpp).
#pragma once

#include <filesystem>
#include <relume/field.hpp>
#include <vector>

namespace relume {

struct FieldSource {
  std::vector<std::filesystem::path> images;  // one per light, in light order
  LightDirections directions;
  LightRgb intensities;        // empty when the field has no light_intensities.txt
  std::filesystem::path mask;  // empty = everything inside
};

// Throws Error naming the file or line at fault: a missing path, a folder that is not a field,
// light files that do not match the images in number.
FieldSource describe_field(const std::filesystem::path& path);

}  // namespace relume
