// Implementation of the weights' camera-domain planes (see weight_planes.hpp).
#include "model/weight_planes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <relume/error.hpp>
#include <string>

namespace relume {
namespace {

// Rows: the components; columns: the channels. Orthonormal, so its inverse is its transpose.
std::array<std::array<double, 3>, 3> colour_transform() {
  const double a = 1 / std::sqrt(3.0), b = 1 / std::sqrt(2.0), c = 1 / std::sqrt(6.0);
  return {{{a, a, a}, {b, -b, 0}, {c, c, -2 * c}}};
}

// The transform's entry (component, channel): the colour transform for three channels, the
// identity otherwise.
double transform_entry(int channels, int component, int channel) {
  if (channels != 3) return component == channel ? 1.0 : 0.0;
  static const auto transform = colour_transform();
  return transform[std::size_t(component)][std::size_t(channel)];
}

std::size_t plane_values(const CompressedField& field) {
  return std::size_t(field.channels) * std::size_t(field.terms) * std::size_t(field.width) *
         std::size_t(field.height);
}

// Stored rows are taken in blocks of this many, plane by plane within a block: a row's values go
// to channels x terms planes far apart, so row by row every value touches another page.
constexpr std::size_t row_block = 512;

// Calls visit(plane, j, r, pixel, entry) for every plane (component a, term j) and every stored row
// r in [first, last) (at most row_block rows) whose channel has a non-zero entry in component a,
// rows ascending.
template <typename Visit>
void for_each_plane_value(const CompressedField& field, std::size_t first, std::size_t last,
                          Visit&& visit) {
  const int channels = field.channels, terms = field.terms;
  std::array<std::size_t, row_block> pixel;
  std::array<double, row_block> entry;  // of each row's channel in component a
  for (std::size_t r = first; r < last; ++r)
    pixel[r - first] = field.stored_function[r] / std::uint32_t(channels);
  for (int a = 0; a < channels; ++a) {
    for (std::size_t r = first; r < last; ++r)
      entry[r - first] =
          transform_entry(channels, a, int(field.stored_function[r] % std::uint32_t(channels)));
    for (int j = 0; j < terms; ++j)
      for (std::size_t r = first; r < last; ++r)
        if (entry[r - first] != 0)
          visit(std::size_t(a) * terms + j, j, r, pixel[r - first], entry[r - first]);
  }
}

}  // namespace

std::vector<float> weight_planes(const CompressedField& field) {
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  std::vector<float> planes(plane_values(field), 0.0f);
  for (std::size_t first = 0; first < field.stored_rows(); first += row_block)
    for_each_plane_value(
        field, first, std::min(field.stored_rows(), first + row_block),
        [&](std::size_t plane, int j, std::size_t r, std::size_t pixel, double entry) {
          planes[plane * area + pixel] += float(entry * field.weights(Eigen::Index(r), j));
        });
  return planes;
}

void set_weights_from_integer_planes(CompressedField& field,
                                     const std::vector<std::int32_t>& samples, float step) {
  if (samples.size() != plane_values(field))
    throw Error("the weight planes hold " + std::to_string(samples.size()) + " values, a " +
                std::to_string(field.width) + "x" + std::to_string(field.height) + " field of " +
                std::to_string(field.channels) + " channels and " + std::to_string(field.terms) +
                " terms has " + std::to_string(plane_values(field)));
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  // Each plane value is float(sample x step), as the codestream decodes; summed over the
  // components in double, in component order, then rounded to float.
  field.weights.resize(Eigen::Index(field.stored_rows()), field.terms);
  std::vector<double> sums;
  for (std::size_t first = 0; first < field.stored_rows(); first += row_block) {
    const std::size_t last = std::min(field.stored_rows(), first + row_block);
    sums.assign((last - first) * std::size_t(field.terms), 0.0);
    for_each_plane_value(
        field, first, last,
        [&](std::size_t plane, int j, std::size_t r, std::size_t pixel, double entry) {
          const float value = float(double(samples[plane * area + pixel]) * step);
          sums[(r - first) * std::size_t(field.terms) + std::size_t(j)] += entry * double(value);
        });
    for (std::size_t r = first; r < last; ++r)
      for (int j = 0; j < field.terms; ++j)
        field.weights(Eigen::Index(r), j) =
            float(sums[(r - first) * std::size_t(field.terms) + std::size_t(j)]);
  }
}

}  // namespace relume
