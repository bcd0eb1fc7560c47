// Implementation of the light weighting's scales and of its residual rows in field units.
#include "compress/light_weighting.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <relume/error.hpp>

namespace relume {

std::vector<float> light_weighting_scales(const ReflectanceField& field, double exponent) {
  if (!(exponent >= 0 && exponent <= 1))
    throw Error("the light weighting must be an exponent in [0, 1], got " +
                std::to_string(exponent));
  const int lights = field.lights();
  std::vector<double> energy(lights, 0.0);
  std::int64_t counted = 0;
  for (std::int64_t q = 0; q < field.pixels(); ++q) {
    if (!field.mask.empty() && !field.mask[std::size_t(q)]) continue;
    for (int c = 0; c < field.channels; ++c, ++counted) {
      const auto row = field.values.row(q * field.channels + c);
      for (int i = 0; i < lights; ++i) energy[i] += double(row[i]) * row[i];
    }
  }
  std::vector<double> rms(lights, 0.0);
  for (int i = 0; i < lights; ++i) rms[i] = counted ? std::sqrt(energy[i] / double(counted)) : 0.0;
  const double peak = lights ? *std::max_element(rms.begin(), rms.end()) : 0.0;
  std::vector<float> scale(lights, 1.0f);
  if (exponent == 0 || !(peak > 0)) return scale;
  for (int i = 0; i < lights; ++i)
    scale[i] = float(std::pow(std::max(rms[i], 1e-3 * peak) / peak, exponent));
  return scale;
}

void unweight_residual_row(ResidualRows& rows, std::size_t begin,
                           const std::vector<float>& light_scale) {
  const std::size_t end = rows.values.size();
  std::vector<std::size_t> order(end - begin);
  std::iota(order.begin(), order.end(), begin);
  for (std::size_t k = begin; k < end; ++k) rows.values[k] *= light_scale[rows.light_index[k]];
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const float x = std::abs(rows.values[a]), y = std::abs(rows.values[b]);
    return x != y ? x > y : rows.light_index[a] < rows.light_index[b];
  });
  std::vector<float> values;
  std::vector<std::uint32_t> lights;
  for (std::size_t k : order) {
    values.push_back(rows.values[k]);
    lights.push_back(rows.light_index[k]);
  }
  std::copy(values.begin(), values.end(), rows.values.begin() + std::ptrdiff_t(begin));
  std::copy(lights.begin(), lights.end(), rows.light_index.begin() + std::ptrdiff_t(begin));
}

}  // namespace relume
