// The percentile exposure of --exposure auto.
#include "image/auto_exposure.hpp"

#include <algorithm>
#include <cmath>

#include "image/luminance.hpp"

namespace relume {

AutoExposure auto_exposure(const Image& image, const std::vector<std::uint8_t>& mask) {
  std::vector<float> lit;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    if (!mask.empty() && !mask[p]) continue;
    const float value = luminance(&image.pixels[p * image.channels], image.channels);
    if (value > 0) lit.push_back(value);
  }
  AutoExposure result;
  result.lit_pixels = lit.size();
  if (lit.empty()) return result;
  const auto at = lit.begin() + static_cast<std::ptrdiff_t>(0.99 * double(lit.size() - 1));
  std::nth_element(lit.begin(), at, lit.end());
  result.percentile = *at;
  result.white = result.percentile / 0.9;
  // Within what write_image accepts: a percentile of 1e-30 or of Inf asks for more than 40 stops.
  result.stops =
      std::clamp(std::log2(0.9 / result.percentile), -max_exposure_stops, max_exposure_stops);
  return result;
}

}  // namespace relume
