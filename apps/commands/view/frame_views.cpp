// Implementation of the error and mask views (frame_views.hpp).
#include "commands/view/frame_views.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "image/auto_exposure.hpp"

namespace relume {
namespace {

using Colour = std::array<float, 3>;

// Display (sRGB-encoded) colours at log10(error / bright level) = -4, -3, -2, -1, 0.
constexpr std::array<Colour, 5> error_ramp = {{{0.05f, 0.05f, 0.35f},
                                               {0.35f, 0.1f, 0.75f},
                                               {0.9f, 0.15f, 0.1f},
                                               {1.0f, 0.9f, 0.1f},
                                               {1.0f, 1.0f, 1.0f}}};

// The linear colour of a relative error (> 0) on the ramp.
Colour ramp_colour(double relative) {
  // NaN (a NaN pixel's error) takes the ramp's first colour rather than an index from nothing.
  const double level = std::log10(relative) + 4.0;
  const double position = level > 0 ? std::min(level, 4.0) : 0.0;
  const int low = std::min(int(position), 3);
  const float t = float(position - low);
  Colour colour;
  for (int c = 0; c < 3; ++c)
    colour[c] = srgb_to_linear((1 - t) * error_ramp[low][c] + t * error_ramp[low + 1][c]);
  return colour;
}

void set_pixel(Image& image, std::size_t pixel, const Colour& colour) {
  for (int c = 0; c < 3; ++c) image.pixels[pixel * 3 + c] = colour[c];
}

}  // namespace

Image false_colour_error(const Image& image, const Image& reference,
                         const std::vector<std::uint8_t>& mask) {
  const double measured = auto_exposure(reference, mask).percentile;
  const double bright = measured > 0 ? measured : 1.0;
  Image view(image.width, image.height, 3);
  const std::size_t pixels = std::size_t(image.width) * image.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    double error = 0;
    for (int c = 0; c < image.channels; ++c)
      error = std::max(error, double(std::abs(image.pixels[p * image.channels + c] -
                                              reference.pixels[p * image.channels + c])));
    if (error > 0) set_pixel(view, p, ramp_colour(error / bright));
  }
  return view;
}

Image absolute_difference(const Image& image, const Image& reference) {
  Image difference(image.width, image.height, image.channels);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    difference.pixels[i] = std::abs(image.pixels[i] - reference.pixels[i]);
  return difference;
}

Image stored_pixels_view(const CompressedField& field) {
  constexpr Colour stored{1, 1, 1}, dark{0.05f, 0.15f, 0.8f}, empty{0.3f, 0.0f, 0.0f};
  Image view(field.width, field.height, 3);
  for (std::size_t p = 0; p < field.mask.size(); ++p)
    if (field.mask[p]) set_pixel(view, p, empty);
  for (const std::uint32_t pixel : field.dark_pixels) set_pixel(view, pixel, dark);
  for (const std::uint32_t function : field.stored_function)
    set_pixel(view, function / field.channels, stored);
  return view;
}

}  // namespace relume
