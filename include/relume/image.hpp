// relume/image.hpp: float images in memory and on disk.
//
// An Image holds interleaved channels, rows top to bottom: the common currency of loaders,
// environment maps, renderers and writers. Reading and writing go through OpenImageIO: integer
// formats are read at their full depth (16-bit PNG as 16 bits) and normalised to [0, 1]; 8-bit
// inputs are linear unless the caller asks for sRGB decoding, or for the automatic choice (sRGB
// unless the file declares a linear colour space). Float outputs (EXR, HDR, TIFF, PFM) are
// written linear (EXR as float or half); integer outputs (PNG and TIFF at 8 or 16 bits, JPEG at
// 8) are exposed by 2^exposure, clamped to [0, 1] and sRGB-encoded. Every written file carries
// relume's version as its Software attribute. All writes are atomic.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

namespace relume {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;  // (y * width + x) * channels + c
  int source_bits = 0;        // read_image: the file's integer depth (8, 16, ...), 0 for floats

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c) {}

  std::size_t index(int x, int y, int c) const {
    return (std::size_t(y) * width + x) * channels + c;
  }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
};

// How 8-bit values are decoded. automatic: by read_image, sRGB unless the file declares a linear
// colour space; by load_field, once per field (field/input_encoding.hpp's rule).
enum class EightBitEncoding { linear, srgb, automatic };

struct ImageReadOptions {
  EightBitEncoding eight_bit = EightBitEncoding::linear;
};

// Throws Error naming the file when it cannot be read.
Image read_image(const std::filesystem::path& path, const ImageReadOptions& options = {});

// The largest exposure magnitude in stops: 2^40 still scales a float pixel finitely.
inline constexpr double max_exposure_stops = 40;

struct ImageWriteOptions {
  double exposure = 0.0;  // stops, within +-max_exposure_stops; applied to integer outputs only
  // Integer outputs: 8 or 16 bits per channel (JPEG: 8 only). 0: the format's default, 8 for
  // PNG and JPEG, linear float for TIFF. TIFF with 8 or 16 is an integer output.
  int bits = 0;
  bool half = false;  // EXR only: half floats (half the bytes, 11-bit precision) instead of float
};

// Throws Error when `options` do not fit the format of `path` (bits other than 0, 8 or 16, 16-bit
// JPEG, bits for a float-only format, half for anything but EXR) or the exposure is not a finite
// number within +-max_exposure_stops. write_image checks the same;
// commands call this before their work.
void check_image_write_options(const std::filesystem::path& path, const ImageWriteOptions& options);

// Format from the extension. Throws Error for NaN/Inf pixels (naming the first), options that do
// not fit the format, or write failure.
void write_image(const std::filesystem::path& path, const Image& image,
                 const ImageWriteOptions& options = {});

// True for extensions written as linear floats by default (exr, hdr, tif, tiff, pfm).
bool is_float_image_format(const std::filesystem::path& path);

// sRGB transfer functions on [0, 1].
float srgb_to_linear(float encoded);
float linear_to_srgb(float linear);

}  // namespace relume
