// OpenImageIO-backed implementation of read_image / write_image.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/version.hpp>
#include <string>

#include "core/atomic_file.hpp"

namespace relume {
namespace fs = std::filesystem;

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Image read_image(const fs::path& path, const ImageReadOptions& options) {
  if (!fs::exists(path)) throw Error("image not found: " + path.string());
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) throw Error("cannot read image " + path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw Error("image " + path.string() + " has no pixels");
  Image image(spec.width, spec.height, spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw Error("cannot decode image " + path.string() + ": " + input->geterror());
  if (!spec.format.is_floating_point()) image.source_bits = int(spec.format.size()) * 8;
  const bool eight_bit = spec.format.basetype == OIIO::TypeDesc::UINT8;
  if (eight_bit && options.eight_bit == EightBitEncoding::srgb)
    for (float& v : image.pixels) v = srgb_to_linear(v);
  return image;
}

bool is_float_image_format(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
}

void write_image(const fs::path& path, const Image& image, const ImageWriteOptions& options) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (!std::isfinite(image.pixels[i])) {
      const std::size_t pixel = i / image.channels;
      throw Error("refusing to write " + path.string() + ": pixel (" +
                  std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) +
                  ") channel " + std::to_string(i % image.channels) + " is " +
                  std::to_string(image.pixels[i]));
    }
  }
  const bool as_float = is_float_image_format(path);
  std::vector<float> data = image.pixels;
  if (!as_float) {
    const float scale = static_cast<float>(std::exp2(options.exposure));
    for (float& v : data) v = linear_to_srgb(std::clamp(v * scale, 0.0f, 1.0f));
  }
  write_atomically(path, [&](const fs::path& temp) {
    auto output = OIIO::ImageOutput::create(path.string());
    if (!output) throw Error("no image writer for " + path.string() + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, image.channels,
                         as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("Software", version_line());
    if (!output->open(temp.string(), spec))
      throw Error("cannot write " + path.string() + ": " + output->geterror());
    if (!output->write_image(OIIO::TypeDesc::FLOAT, data.data()) || !output->close())
      throw Error("cannot write " + path.string() + ": " + output->geterror());
  });
}

}  // namespace relume
