// Black pixels, chroma outliers and channel sums of a relit image (see lit_pixel_faults.hpp).
#include "image/lit_pixel_faults.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "image/auto_exposure.hpp"
#include "image/image_difference.hpp"
#include "image/luminance.hpp"

namespace relume {
namespace {

// r, g, b / (r + g + b) with negative values as 0; nullopt when nothing is positive.
std::optional<std::array<double, 3>> chromaticity(const float* pixel) {
  const std::array<double, 3> value = {std::max(0.0f, pixel[0]), std::max(0.0f, pixel[1]),
                                       std::max(0.0f, pixel[2])};
  const double sum = value[0] + value[1] + value[2];
  if (sum <= 0) return std::nullopt;
  return std::array<double, 3>{value[0] / sum, value[1] / sum, value[2] / sum};
}

}  // namespace

LitPixelFaults lit_pixel_faults(const Image& image, const Image& reference,
                                const std::vector<std::uint8_t>& mask,
                                const std::string& image_label,
                                const std::string& reference_label) {
  check_comparable(image, reference, image_label, reference_label, mask);
  const int channels = image.channels;
  const std::size_t pixels = std::size_t(image.width) * image.height;
  const auto inside = [&](std::size_t p) { return mask.empty() || mask[p] != 0; };
  LitPixelFaults result;
  result.white = auto_exposure(reference, mask).white;
  std::vector<double> image_sums(channels, 0.0), reference_sums(channels, 0.0);
  for (std::size_t p = 0; p < pixels; ++p) {
    if (!inside(p)) continue;
    for (int c = 0; c < channels; ++c) {
      image_sums[c] += image.pixels[p * channels + c];
      reference_sums[c] += reference.pixels[p * channels + c];
    }
  }
  for (int c = 0; c < channels; ++c)
    result.channel_sum_ratio.push_back(
        reference_sums[c] != 0 ? std::optional<double>(image_sums[c] / reference_sums[c])
                               : std::nullopt);
  if (result.white <= 0) return result;
  for (std::size_t p = 0; p < pixels; ++p) {
    const float* relit = &image.pixels[p * channels];
    const float* original = &reference.pixels[p * channels];
    if (!inside(p) || luminance(original, channels) < lit_luminance_share * result.white) continue;
    ++result.lit_pixels;
    const PixelPosition at{int(p % image.width), int(p / image.width)};
    if (luminance(relit, channels) < black_luminance_share * result.white) {
      if (result.black_examples.size() < black_examples_kept) result.black_examples.push_back(at);
      ++result.black_pixels;
    }
    if (channels < 3) continue;
    const auto relit_colour = chromaticity(relit), original_colour = chromaticity(original);
    double difference = 1;  // no colour at all
    if (relit_colour) {
      difference = 0;
      for (int c = 0; c < 3; ++c)
        difference = std::max(difference, std::abs((*relit_colour)[c] - (*original_colour)[c]));
    }
    if (difference > chroma_outlier_tolerance) ++result.chroma_outliers;
    if (difference > result.largest_chroma_difference) {
      result.largest_chroma_difference = difference;
      result.largest_chroma_at = at;
    }
  }
  return result;
}

}  // namespace relume
