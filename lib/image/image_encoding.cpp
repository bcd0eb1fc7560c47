// Reading an image's declared encoding through OpenImageIO.
#include "image/image_encoding.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <relume/error.hpp>

#include "image/png_chunks.hpp"

namespace relume {

namespace {

std::string declared_color_space(const OIIO::ImageSpec& spec) {
  const std::string tagged = spec.get_string_attribute("oiio:ColorSpace");
  if (!tagged.empty()) return tagged;
  if (spec.get_int_attribute("Exif:ColorSpace", 0) == 1) return "sRGB";
  return "";
}

}  // namespace

StoredEncoding read_stored_encoding(const std::filesystem::path& path) {
  check_png_chunks(path);
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) throw Error("cannot read image " + path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  StoredEncoding encoding;
  encoding.format = input->format_name();
  encoding.bits = static_cast<int>(spec.format.size() * 8);
  encoding.floating = spec.format.is_floating_point();
  encoding.color_space = declared_color_space(spec);
  return encoding;
}

bool is_linear_color_space(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  for (const char* linear : {"linear", "scene_linear", "lin_srgb", "lin_rec709", "acescg", "aces"})
    if (lower == linear) return true;
  return false;
}

}  // namespace relume
