// How far an image is from a reference image of the same size: the relative squared error (the
// per-image form of paper Eq. 16, sum (a - r)^2 / sum r^2), the largest absolute difference and
// where it is, and how many values are negative (a relit compressed field can undershoot zero,
// which an 8-bit output then shows as black), the largest relative difference (|a - r| over
// max(|r|, 1% of the reference's peak): a crescent relit 90% too dark shows as 0.9 however dim
// it is, and black reference pixels do not divide by zero) and where it is, and the mean squared
// difference behind RMS and PSNR. A mask restricts every figure to the pixels inside. And the
// difference itself as an image, scaled to be seen.
#pragma once

#include <cstdint>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

struct ImageDifference {
  // 0 when both images are all zero, 1 when only the reference is.
  double relative_squared_error = 0;
  double mean_squared_difference = 0;  // over the compared values; RMS is its square root
  double max_abs_difference = 0;
  int max_x = 0, max_y = 0, max_channel = 0;  // where the largest difference is
  // max |a - r| / max(|r|, relative_difference_floor * the reference's largest |r|); 0 when the
  // reference is all zero
  double max_relative_difference = 0;
  int relative_x = 0, relative_y = 0, relative_channel = 0;  // where it is
  std::size_t negative_values = 0;                           // in the image (not the reference)
  std::size_t values = 0;                                    // compared (inside the mask)
};

// The share of the reference's peak below which max_relative_difference divides by that share.
inline constexpr double relative_difference_floor = 0.01;

// PSNR in dB for a peak value of 1 (the full range of 8- and 16-bit images, as idiff takes it):
// 10 log10(1 / mean squared difference); +infinity for identical images.
double peak_signal_to_noise_db(const ImageDifference& difference);

// "WxH with C channels": how the size checks of the comparisons name an image or a field.
std::string size_and_channels_text(int width, int height, int channels);

// Throws Error naming both labels when the images differ in size or channels, or naming the image
// when `mask` (width * height entries, or empty) does not fit it: the check of every comparison
// of two images (this one, the luminance SSIM, the lit pixel faults, the seam contrast).
void check_comparable(const Image& image, const Image& reference, const std::string& image_label,
                      const std::string& reference_label, const std::vector<std::uint8_t>& mask);

// `mask`: width * height entries, 1 = compared; empty compares every pixel. Throws Error as
// check_comparable does, and when either image holds NaN or Inf.
ImageDifference image_difference(const Image& image, const Image& reference,
                                 const std::string& image_label = "image",
                                 const std::string& reference_label = "reference",
                                 const std::vector<std::uint8_t>& mask = {});

// |image - reference| x scale, per value: a difference image to look at. Throws Error as
// check_comparable does.
Image scaled_difference(const Image& image, const Image& reference, float scale);

}  // namespace relume
