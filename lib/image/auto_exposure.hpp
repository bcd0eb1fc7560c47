// --exposure auto: the exposure that shows a relit object well on an integer (8/16-bit sRGB)
// output. The 99th percentile of the luminance of the lit object (pixels inside the mask with a
// luminance above zero) is mapped to 0.9 in linear terms, before the sRGB curve: the brightest
// 1% may clip, highlights keep headroom, and a black background does not count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <relume/image.hpp>
#include <vector>

namespace relume {

struct AutoExposure {
  double stops = 0;       // the exposure, within +-max_exposure_stops; 0 when nothing is lit
  double percentile = 0;  // the luminance that maps to 0.9
  double white = 0;       // the luminance that maps to 1 (percentile / 0.9); 0 when nothing is lit
  std::size_t lit_pixels = 0;
};

// Luminance: image/luminance.hpp.
// `mask`: width * height entries, 1 = part of the object; empty = the whole image.
AutoExposure auto_exposure(const Image& image, const std::vector<std::uint8_t>& mask);

}  // namespace relume
