// Structural similarity (SSIM, Wang, Bovik, Sheikh and Simoncelli 2004) of the luminance of an
// image against a reference, as a person sees them: how much of the local structure (mean,
// contrast, correlation) a relit image keeps, which a squared error averages away. Both images
// are shown the way --exposure auto shows the reference (image/auto_exposure.hpp): the
// luminance (image/luminance.hpp) over the reference's white (its lit 99th percentile / 0.9),
// clipped to [0, 1] and sRGB-encoded, so SSIM sees display values with L = 1 as Wang et al.
// define it, and a highlight 70 times the white does not flatten everything else. One window
// per pixel of the compared area: Gaussian weights of sigma 1.5 over the 11 x 11 pixels around
// it, restricted to the pixels inside both the image and the area and renormalised to sum 1 (a
// window at the border of the mask sees only the object). Per window,
//   SSIM = (2 mu_a mu_r + C1) (2 cov_ar + C2) / ((mu_a^2 + mu_r^2 + C1) (var_a + var_r + C2)),
// C1 = 0.01^2, C2 = 0.03^2. Reported: the mean over the windows, the worst 1% (the value that 1%
// of the windows are at or below) and the worst window with its centre.
#pragma once

#include <cstddef>
#include <cstdint>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

inline constexpr int ssim_window_radius = 5;  // 11 x 11 windows
inline constexpr double ssim_window_sigma = 1.5;

struct LuminanceSsim {
  double mean = 1;             // over the windows; 1 when there are none
  double worst_1_percent = 1;  // the 1st percentile of the windows' values
  double minimum = 1;
  int minimum_x = 0, minimum_y = 0;  // the worst window's centre
  std::size_t windows = 0;           // one per pixel of the area
  double white = 0;                  // the reference's luminance shown as 1; 0: nothing is lit
};

// `mask`: width * height entries, 1 = compared; empty: the whole image. Throws Error as
// check_comparable (image/image_difference.hpp) does.
LuminanceSsim luminance_ssim(const Image& image, const Image& reference,
                             const std::vector<std::uint8_t>& mask = {},
                             const std::string& image_label = "image",
                             const std::string& reference_label = "reference");

}  // namespace relume
