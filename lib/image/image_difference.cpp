// Implementation of the image comparison (see image_difference.hpp).
#include "image/image_difference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <relume/error.hpp>

namespace relume {

double peak_signal_to_noise_db(const ImageDifference& difference) {
  if (difference.mean_squared_difference == 0) return std::numeric_limits<double>::infinity();
  return -10.0 * std::log10(difference.mean_squared_difference);
}

std::string size_and_channels_text(int width, int height, int channels) {
  return std::to_string(width) + "x" + std::to_string(height) + " with " +
         std::to_string(channels) + " channels";
}

void check_comparable(const Image& image, const Image& reference, const std::string& image_label,
                      const std::string& reference_label, const std::vector<std::uint8_t>& mask) {
  if (image.width != reference.width || image.height != reference.height ||
      image.channels != reference.channels)
    throw Error(image_label + " is " +
                size_and_channels_text(image.width, image.height, image.channels) + ", " +
                reference_label + " is " +
                size_and_channels_text(reference.width, reference.height, reference.channels));
  if (!mask.empty() && mask.size() != std::size_t(image.width) * image.height)
    throw Error("the mask has " + std::to_string(mask.size()) + " pixels but " + image_label +
                " has " + std::to_string(std::size_t(image.width) * image.height));
}

ImageDifference image_difference(const Image& image, const Image& reference,
                                 const std::string& image_label, const std::string& reference_label,
                                 const std::vector<std::uint8_t>& mask) {
  check_comparable(image, reference, image_label, reference_label, mask);
  const auto inside = [&](std::size_t i) { return mask.empty() || mask[i / image.channels]; };
  double reference_peak = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (!inside(i)) continue;
    const double a = image.pixels[i], r = reference.pixels[i];
    if (!std::isfinite(a) || !std::isfinite(r)) {
      const std::size_t pixel = i / image.channels;
      throw Error((std::isfinite(a) ? reference_label : image_label) + ": pixel (" +
                  std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) +
                  ") channel " + std::to_string(i % image.channels) + " is " +
                  std::to_string(std::isfinite(a) ? r : a) + ", expected a finite value");
    }
    reference_peak = std::max(reference_peak, std::abs(r));
  }
  const double relative_floor = relative_difference_floor * reference_peak;
  ImageDifference result;
  double difference = 0, energy = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (!inside(i)) continue;
    ++result.values;
    const double a = image.pixels[i], r = reference.pixels[i];
    const double d = a - r;
    difference += d * d;
    energy += r * r;
    if (a < 0) ++result.negative_values;
    if (std::abs(d) > result.max_abs_difference) {
      const std::size_t pixel = i / image.channels;
      result.max_abs_difference = std::abs(d);
      result.max_x = int(pixel % image.width);
      result.max_y = int(pixel / image.width);
      result.max_channel = int(i % image.channels);
    }
    const double scale = std::max(std::abs(r), relative_floor);  // 0: the reference is all zero
    const double relative = scale > 0 ? std::abs(d) / scale : 0.0;
    if (relative > result.max_relative_difference) {
      const std::size_t pixel = i / image.channels;
      result.max_relative_difference = relative;
      result.relative_x = int(pixel % image.width);
      result.relative_y = int(pixel / image.width);
      result.relative_channel = int(i % image.channels);
    }
  }
  result.mean_squared_difference = result.values > 0 ? difference / double(result.values) : 0;
  result.relative_squared_error = energy > 0 ? difference / energy : (difference > 0 ? 1.0 : 0.0);
  return result;
}

Image scaled_difference(const Image& image, const Image& reference, float scale) {
  check_comparable(image, reference, "image", "reference", {});
  Image out(image.width, image.height, image.channels);
  for (std::size_t v = 0; v < out.pixels.size(); ++v)
    out.pixels[v] = std::fabs(image.pixels[v] - reference.pixels[v]) * scale;
  return out;
}

}  // namespace relume
