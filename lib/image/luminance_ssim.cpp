// The windowed SSIM of the displayed luminance (see luminance_ssim.hpp).
#include "image/luminance_ssim.hpp"

#include <algorithm>
#include <cmath>

#include "image/auto_exposure.hpp"
#include "image/image_difference.hpp"
#include "image/luminance.hpp"

namespace relume {
namespace {

// The luminance of every pixel over `white`, clipped to [0, 1] and sRGB-encoded.
std::vector<double> displayed_luminance(const Image& image, double white) {
  std::vector<double> plane(std::size_t(image.width) * image.height);
  for (std::size_t p = 0; p < plane.size(); ++p) {
    const double shown = luminance(&image.pixels[p * image.channels], image.channels) / white;
    plane[p] = linear_to_srgb(float(std::clamp(shown, 0.0, 1.0)));
  }
  return plane;
}

}  // namespace

LuminanceSsim luminance_ssim(const Image& image, const Image& reference,
                             const std::vector<std::uint8_t>& mask, const std::string& image_label,
                             const std::string& reference_label) {
  check_comparable(image, reference, image_label, reference_label, mask);
  const int width = image.width, height = image.height;
  const auto inside = [&](std::size_t p) { return mask.empty() || mask[p] != 0; };
  LuminanceSsim result;
  result.white = auto_exposure(reference, mask).white;
  const double white = result.white > 0 ? result.white : 1.0;
  const std::vector<double> a = displayed_luminance(image, white);
  const std::vector<double> r = displayed_luminance(reference, white);
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double gaussian[ssim_window_radius + 1];
  for (int d = 0; d <= ssim_window_radius; ++d)
    gaussian[d] = std::exp(-d * d / (2 * ssim_window_sigma * ssim_window_sigma));

  std::vector<double> values;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!inside(std::size_t(y) * width + x)) continue;
      double weights = 0, mean_a = 0, mean_r = 0, square_a = 0, square_r = 0, product = 0;
      for (int v = std::max(0, y - ssim_window_radius);
           v <= std::min(height - 1, y + ssim_window_radius); ++v)
        for (int u = std::max(0, x - ssim_window_radius);
             u <= std::min(width - 1, x + ssim_window_radius); ++u) {
          const std::size_t q = std::size_t(v) * width + u;
          if (!inside(q)) continue;
          const double w = gaussian[std::abs(u - x)] * gaussian[std::abs(v - y)];
          weights += w;
          mean_a += w * a[q];
          mean_r += w * r[q];
          square_a += w * a[q] * a[q];
          square_r += w * r[q] * r[q];
          product += w * a[q] * r[q];
        }
      mean_a /= weights;
      mean_r /= weights;
      const double variance_a = std::max(0.0, square_a / weights - mean_a * mean_a);
      const double variance_r = std::max(0.0, square_r / weights - mean_r * mean_r);
      const double covariance = product / weights - mean_a * mean_r;
      const double ssim =
          (2 * mean_a * mean_r + c1) * (2 * covariance + c2) /
          ((mean_a * mean_a + mean_r * mean_r + c1) * (variance_a + variance_r + c2));
      if (values.empty() || ssim < result.minimum) {
        result.minimum = ssim;
        result.minimum_x = x;
        result.minimum_y = y;
      }
      values.push_back(ssim);
    }
  result.windows = values.size();
  if (values.empty()) return result;
  double sum = 0;
  for (const double value : values) sum += value;
  result.mean = sum / double(values.size());
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(0.01 * double(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  result.worst_1_percent = *at;
  return result;
}

}  // namespace relume
