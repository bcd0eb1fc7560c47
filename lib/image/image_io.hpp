// Reading and writing images through OpenImageIO. Integer formats are read at their full depth
// (16-bit PNG as 16 bits) and normalised to [0, 1]. 8-bit inputs are linear unless the caller asks
// for sRGB decoding. Float outputs (EXR, HDR, TIFF) are written linear; 8-bit outputs (PNG, JPEG)
// are exposed by 2^exposure and sRGB-encoded. All writes are atomic.
#pragma once

#include <filesystem>

#include "image/image.hpp"

namespace relume {

enum class EightBitEncoding { linear, srgb };

struct ImageReadOptions {
  EightBitEncoding eight_bit = EightBitEncoding::linear;
};

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
