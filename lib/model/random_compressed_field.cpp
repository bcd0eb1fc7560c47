// Implementation of the seeded random compressed field.
#include "model/random_compressed_field.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <relume/error.hpp>
#include <string>

namespace relume {

CompressedField random_compressed_field(const RandomFieldShape& shape) {
  if (shape.width <= 0 || shape.height <= 0 || shape.channels <= 0 || shape.lights <= 0 ||
      shape.clusters <= 0 || shape.terms <= 0)
    throw Error(
        "random field: width, height, channels, lights, clusters and terms must be "
        "positive (got " +
        std::to_string(shape.width) + "x" + std::to_string(shape.height) + "x" +
        std::to_string(shape.channels) + ", " + std::to_string(shape.lights) + " lights, " +
        std::to_string(shape.clusters) + " clusters, " + std::to_string(shape.terms) + " terms)");
  if (shape.residual_per_function < 0 || shape.residual_per_function > shape.lights)
    throw Error("random field: " + std::to_string(shape.residual_per_function) +
                " residual entries per function (expected 0 to the light count " +
                std::to_string(shape.lights) + ")");
  if (!(shape.stored_fraction >= 0 && shape.stored_fraction <= 1))
    throw Error("random field: stored fraction " + std::to_string(shape.stored_fraction) +
                " (expected 0 to 1)");

  std::mt19937_64 random(shape.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> symmetric(-1.0f, 1.0f);
  std::normal_distribution<float> residual_value(0.0f, 0.1f);

  CompressedField field;
  field.width = shape.width;
  field.height = shape.height;
  field.channels = shape.channels;
  field.lights = shape.lights;
  field.terms = shape.terms;
  field.clusters = shape.clusters;
  field.mask.assign(std::size_t(shape.width) * shape.height, 0);
  field.directions.resize(shape.lights, 3);
  for (int i = 0; i < shape.lights; ++i) {
    Eigen::Vector3f direction(symmetric(random), symmetric(random), unit(random) + 0.1f);
    field.directions.row(i) = direction.normalized().transpose();
  }
  field.intensities = LightRgb::Ones(shape.lights, 3);

  for (std::int64_t p = 0; p < field.functions(); ++p)
    if (shape.stored_fraction >= 1 || unit(random) < shape.stored_fraction) {
      field.stored_function.push_back(std::uint32_t(p));
      field.mask[std::size_t(p / shape.channels)] = 1;
    }
  const std::size_t rows = field.stored_rows();
  std::uniform_int_distribution<std::uint32_t> cluster_id(0, std::uint32_t(shape.clusters - 1));
  field.cluster.resize(rows);
  for (auto& k : field.cluster) k = cluster_id(random);
  field.weights.resize(Eigen::Index(rows), shape.terms);
  for (Eigen::Index i = 0; i < field.weights.size(); ++i)
    field.weights.data()[i] = symmetric(random);
  field.bases.resize(std::size_t(shape.clusters) * shape.terms * shape.lights);
  for (auto& value : field.bases) value = unit(random);

  auto& residual = field.residual;
  residual.row_offsets.assign(1, 0);
  std::vector<std::uint32_t> lights(std::size_t(shape.lights));
  std::iota(lights.begin(), lights.end(), 0u);
  std::uniform_int_distribution<int> entry_count(0, shape.residual_per_function);
  std::vector<std::pair<float, std::uint32_t>> row;
  for (std::size_t s = 0; s < rows; ++s) {
    const int count = shape.vary_residual ? entry_count(random) : shape.residual_per_function;
    row.clear();
    for (int e = 0; e < count; ++e) {  // partial Fisher-Yates: distinct lights
      std::uniform_int_distribution<int> pick(e, shape.lights - 1);
      std::swap(lights[std::size_t(e)], lights[std::size_t(pick(random))]);
      row.emplace_back(residual_value(random), lights[std::size_t(e)]);
    }
    std::sort(row.begin(), row.end(),
              [](const auto& a, const auto& b) { return std::abs(a.first) > std::abs(b.first); });
    for (const auto& [value, light] : row) {
      residual.values.push_back(value);
      residual.light_index.push_back(light);
    }
    residual.row_offsets.push_back(std::uint32_t(residual.values.size()));
  }
  return field;
}

LightRgb random_light_vector(int lights, std::uint64_t seed) {
  if (lights <= 0)
    throw Error("random light vector: " + std::to_string(lights) + " lights (expected positive)");
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  LightRgb light(lights, 3);
  for (Eigen::Index i = 0; i < light.size(); ++i) light.data()[i] = unit(random);
  return light;
}

}  // namespace relume
