// What a person sees wrong in single pixels of a relit image that a squared error averages away:
// pixels gone black where the reference is lit, pixels whose colour is off, and a colour cast over
// the whole object. Relative to the reference's white W, the luminance (image/luminance.hpp) that
// --exposure auto shows as 1 (image/auto_exposure.hpp: its lit 99th percentile / 0.9), so the
// figures depend neither on the exposure nor on a few highlights far above the rest:
//   - a lit pixel: its reference luminance is at least 2/255 of W (two codes above black in a
//     linear 8-bit image exposed to W);
//   - a black pixel: a lit pixel whose luminance in the image is below 1/255 of W (a relit value
//     clamped to 0 is one). The factor 2 between the two thresholds keeps a pixel at the edge of
//     black that moves by a hair from counting;
//   - a chroma outlier (3 or more channels): a lit pixel whose chromaticity r, g, b / (r + g + b)
//     differs from the reference's by more than 0.05 in some channel, negative values taken as 0;
//     an image pixel with no positive value has no colour and counts as an outlier;
//   - the channel sums ratio: per channel, the image's sum over the area / the reference's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

inline constexpr double lit_luminance_share = 2.0 / 255;    // of the white: a lit pixel
inline constexpr double black_luminance_share = 1.0 / 255;  // of the white: a black pixel
inline constexpr double chroma_outlier_tolerance = 0.05;

struct PixelPosition {
  int x = 0, y = 0;
};

struct LitPixelFaults {
  double white = 0;  // W; 0 when the reference is black inside the area
  std::size_t lit_pixels = 0;
  std::size_t black_pixels = 0;
  std::vector<PixelPosition> black_examples;  // the first few black pixels in scan order
  std::size_t chroma_outliers = 0;            // 0 for images of fewer than 3 channels
  double largest_chroma_difference = 0;       // over the lit pixels and channels
  PixelPosition largest_chroma_at;
  // Per channel; nullopt where the reference's sum is 0.
  std::vector<std::optional<double>> channel_sum_ratio;
};

inline constexpr std::size_t black_examples_kept = 8;

// `mask`: width * height entries, 1 = compared; empty: the whole image. Throws Error as
// check_comparable (image/image_difference.hpp) does.
LitPixelFaults lit_pixel_faults(const Image& image, const Image& reference,
                                const std::vector<std::uint8_t>& mask = {},
                                const std::string& image_label = "image",
                                const std::string& reference_label = "reference");

}  // namespace relume
