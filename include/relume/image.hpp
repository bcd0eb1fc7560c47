// relume/image.hpp: float images in memory and on disk.
//
// An Image holds interleaved channels, rows top to bottom: the common currency of loaders,
// environment maps, renderers and writers. Reading and writing go through OpenImageIO: integer
// formats are read at their full depth (16-bit PNG as 16 bits) and normalised to [0, 1]; 8-bit
// inputs are linear unless the caller asks for sRGB decoding. Float outputs (EXR, HDR, TIFF) are
// written linear; 8-bit outputs (PNG, JPEG) are exposed by 2^exposure and sRGB-encoded. Every
// written file carries relume's version as its Software attribute. All writes are atomic.
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

enum class EightBitEncoding { linear, srgb };

struct ImageReadOptions {
  EightBitEncoding eight_bit = EightBitEncoding::linear;
};

// Throws Error naming the file when it cannot be read.
Image read_image(const std::filesystem::path& path, const ImageReadOptions& options = {});

struct ImageWriteOptions {
  double exposure = 0.0;  // stops; applied to 8-bit outputs only
};

// Format from the extension. Throws Error for NaN/Inf pixels (naming the first) or write failure.
void write_image(const std::filesystem::path& path, const Image& image,
                 const ImageWriteOptions& options = {});

// True for extensions written as linear floats (exr, hdr, tif, tiff, pfm).
bool is_float_image_format(const std::filesystem::path& path);

// sRGB transfer functions on [0, 1].
float srgb_to_linear(float encoded);
float linear_to_srgb(float linear);

}  // namespace relume
