// What an image file says about how its values are encoded, read from its header without
// decoding pixels: the format, the bits per channel, whether they are floating point, and the
// colour space it declares (OpenImageIO's oiio:ColorSpace, or Exif ColorSpace 1 = sRGB). Input
// encoding decisions are made from this (field/input_encoding.hpp).
#pragma once

#include <filesystem>
#include <string>

namespace relume {

struct StoredEncoding {
  std::string format;       // OpenImageIO's name: "png", "jpeg", "openexr", "hdr", "tiff", ...
  int bits = 0;             // per channel
  bool floating = false;    // half, float or double values
  std::string color_space;  // as declared ("sRGB", "linear", ...); empty when none is
};

// Throws Error naming the file when it cannot be opened.
StoredEncoding read_stored_encoding(const std::filesystem::path& path);

// True for colour-space names that mean linear values ("linear", "scene_linear", "lin_srgb",
// "ACEScg", ... in any case).
bool is_linear_color_space(const std::string& name);

}  // namespace relume
