// Implementation of the weights' camera-domain planes (see weight_planes.hpp).
#include "model/weight_planes.hpp"

#include <array>
#include <cmath>
#include <relume/error.hpp>

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

}  // namespace

std::vector<float> weight_planes(const CompressedField& field) {
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  const int channels = field.channels, terms = field.terms;
  std::vector<float> planes(plane_values(field), 0.0f);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::size_t pixel = field.stored_function[r] / std::size_t(channels);
    const int channel = int(field.stored_function[r] % std::size_t(channels));
    for (int a = 0; a < channels; ++a) {
      const double entry = transform_entry(channels, a, channel);
      if (entry == 0) continue;
      for (int j = 0; j < terms; ++j)
        planes[(std::size_t(a) * terms + j) * area + pixel] +=
            float(entry * field.weights(Eigen::Index(r), j));
    }
  }
  return planes;
}

void set_weights_from_planes(CompressedField& field, const std::vector<float>& planes) {
  if (planes.size() != plane_values(field))
    throw Error("the weight planes hold " + std::to_string(planes.size()) + " values, a " +
                std::to_string(field.width) + "x" + std::to_string(field.height) + " field of " +
                std::to_string(field.channels) + " channels and " + std::to_string(field.terms) +
                " terms has " + std::to_string(plane_values(field)));
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  const int channels = field.channels, terms = field.terms;
  field.weights.setZero(Eigen::Index(field.stored_rows()), terms);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::size_t pixel = field.stored_function[r] / std::size_t(channels);
    const int channel = int(field.stored_function[r] % std::size_t(channels));
    for (int j = 0; j < terms; ++j) {
      double weight = 0;
      for (int a = 0; a < channels; ++a)
        weight += transform_entry(channels, a, channel) *
                  double(planes[(std::size_t(a) * terms + j) * area + pixel]);
      field.weights(Eigen::Index(r), j) = float(weight);
    }
  }
}

}  // namespace relume
