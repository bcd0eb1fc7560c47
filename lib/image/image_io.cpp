// OpenImageIO-backed implementation of read_image / write_image, and of encode_image_bytes
// (image/image_bytes.hpp), which encodes the same way into memory.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/version.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "core/text_numbers.hpp"
#include "image/image_bytes.hpp"
#include "image/image_encoding.hpp"
#include "image/image_rows.hpp"
#include "image/srgb_codes.hpp"

namespace relume {
namespace fs = std::filesystem;

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Image read_image(const fs::path& path, const ImageReadOptions& options) {
  ImageRowReader reader(path, options);
  check_memory_need(std::uint64_t(reader.width()) * std::uint64_t(reader.height()) *
                        std::uint64_t(reader.channels()) * sizeof(float),
                    "image " + path.string() + " (" + std::to_string(reader.width()) + "x" +
                        std::to_string(reader.height()) + ", " + std::to_string(reader.channels()) +
                        " channels)");
  Image image(reader.width(), reader.height(), reader.channels());
  reader.read_rows(0, reader.height(), image.pixels.data());
  image.source_bits = reader.source_bits();
  return image;
}

namespace {

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext;
}

bool is_tiff(const std::string& ext) { return ext == ".tif" || ext == ".tiff"; }

// Whether `path` with `options` is written as linear floats (else exposed, sRGB integers).
bool writes_float(const fs::path& path, const ImageWriteOptions& options) {
  return is_tiff(lower_extension(path)) ? options.bits == 0 : is_float_image_format(path);
}

}  // namespace

bool is_float_image_format(const fs::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".exr" || ext == ".hdr" || is_tiff(ext) || ext == ".pfm";
}

void check_image_write_options(const fs::path& path, const ImageWriteOptions& options) {
  const std::string ext = lower_extension(path);
  if (!(std::abs(options.exposure) <= max_exposure_stops))
    throw Error(path.string() + ": exposure " + number_text(options.exposure) +
                " stops is out of range (from -" + number_text(max_exposure_stops) + " to " +
                number_text(max_exposure_stops) + ")");
  if (options.bits != 0 && options.bits != 8 && options.bits != 16)
    throw Error(path.string() + ": integer images have 8 or 16 bits per channel, not " +
                std::to_string(options.bits));
  if (options.bits != 0 && is_float_image_format(path) && !is_tiff(ext))
    throw Error(path.string() + ": " + ext + " holds floats; bits apply to PNG, TIFF and JPEG");
  if ((ext == ".jpg" || ext == ".jpeg") && options.bits == 16)
    throw Error(path.string() + ": JPEG holds 8 bits per channel; write PNG or TIFF for 16");
  if (options.half && ext != ".exr")
    throw Error(path.string() + ": half floats are for EXR outputs only");
}

namespace {

// Throws Error naming `path` when `options` do not fit its format or a pixel is NaN or Inf.
void check_writable(const fs::path& path, const Image& image, const ImageWriteOptions& options) {
  check_image_write_options(path, options);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (!std::isfinite(image.pixels[i])) {
      const std::size_t pixel = i / image.channels;
      throw Error("refusing to write " + path.string() + ": pixel (" +
                  std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) +
                  ") channel " + std::to_string(i % image.channels) + " is " +
                  std::to_string(image.pixels[i]));
    }
  }
}

// Encodes `image` (checked by check_writable) as the format of `path` (its extension; also named
// in messages) into `target`: a file name or, with `proxy`, the name opened through the proxy.
void encode_image(const fs::path& path, const std::string& target, OIIO::Filesystem::IOProxy* proxy,
                  const Image& image, const ImageWriteOptions& options) {
  const bool as_float = writes_float(path, options);
  const bool eight_bit = !as_float && options.bits != 16;
  const float scale = static_cast<float>(std::exp2(options.exposure));
  // Integer outputs: exposed, clamped, sRGB-encoded; 8 bits straight to their codes by table.
  std::vector<float> data;
  std::vector<std::uint8_t> codes;
  if (eight_bit) {
    codes.resize(image.pixels.size());
    for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = srgb_code(image.pixels[i] * scale);
  } else {
    data = image.pixels;
    if (!as_float)
      for (float& v : data) v = linear_to_srgb(unit_clamped(v * scale));
  }
  const OIIO::TypeDesc stored = as_float
                                    ? (options.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT)
                                    : (eight_bit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
  auto output = OIIO::ImageOutput::create(path.string());
  if (!output) throw Error("no image writer for " + path.string() + ": " + OIIO::geterror());
  if (proxy && !output->set_ioproxy(proxy))
    throw Error("the " + path.extension().string() + " writer cannot write to memory");
  OIIO::ImageSpec spec(image.width, image.height, image.channels, stored);
  spec.attribute("Software", version_line());
  if (!output->open(target, spec))
    throw Error("cannot write " + path.string() + ": " + output->geterror());
  const bool written = eight_bit ? output->write_image(OIIO::TypeDesc::UINT8, codes.data())
                                 : output->write_image(OIIO::TypeDesc::FLOAT, data.data());
  if (!written || !output->close())
    throw Error("cannot write " + path.string() + ": " + output->geterror());
}

}  // namespace

void write_image(const fs::path& path, const Image& image, const ImageWriteOptions& options) {
  check_writable(path, image, options);
  write_atomically(path, [&](const fs::path& temp) {
    encode_image(path, temp.string(), nullptr, image, options);
  });
}

std::string encode_image_bytes(const std::string& extension, const Image& image,
                               const ImageWriteOptions& options) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const std::string name = "memory" + extension;
  check_writable(name, image, options);
  encode_image(name, name, &memory, image, options);
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace relume
