// Implementation of the noise estimate and the dark test's settings (see noise_model.hpp).
#include "compress/noise_model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <relume/error.hpp>
#include <string>

#include "compress/cluster_model.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace {

// Median absolute deviation to standard deviation, for normal noise.
constexpr double mad_to_sigma = 1.0 / 0.6745;
// Fewer diagonal coefficients than this in an image say nothing about its noise.
constexpr std::size_t min_coefficients = 16;
// Blocks enough for both estimates (a few percent on their own), at bounded memory.
constexpr std::size_t max_blocks = 100000;

bool inside(const ReflectanceField& field, int x, int y) {
  return field.mask.empty() || field.mask[std::size_t(y) * field.width + x] != 0;
}

double median(std::vector<double>& values) {
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The finest diagonal Haar coefficients (a - b - c + d) / 2 of channel c: one row per 2x2 block
// wholly inside the mask (at most max_blocks of them, evenly spread), one column per light.
Eigen::MatrixXf diagonal_coefficients(const ReflectanceField& field, int c) {
  std::vector<std::int64_t> blocks;  // top-left pixel of each block
  for (int y = 0; y + 1 < field.height; y += 2)
    for (int x = 0; x + 1 < field.width; x += 2)
      if (inside(field, x, y) && inside(field, x + 1, y) && inside(field, x, y + 1) &&
          inside(field, x + 1, y + 1))
        blocks.push_back(std::int64_t(y) * field.width + x);
  const std::size_t stride = std::max<std::size_t>(1, blocks.size() / max_blocks);
  Eigen::MatrixXf coefficients((blocks.size() + stride - 1) / stride, field.lights());
  for (std::size_t b = 0; b < std::size_t(coefficients.rows()); ++b) {
    const std::int64_t q = blocks[b * stride];
    const auto row = [&](std::int64_t pixel) {
      return field.values.row(pixel * field.channels + c);
    };
    coefficients.row(std::int64_t(b)) =
        (row(q) - row(q + 1) - row(q + field.width) + row(q + field.width + 1)) / 2;
  }
  return coefficients;
}

// The smaller of two estimates of the noise deviation from the coefficients: the median over the
// lights of each image's median |coefficient| / 0.6745 (robust to outliers, raised by texture),
// and the root of the median eigenvalue of their covariance over the lights (texture and shading
// vary over the lights in a few directions, noise in all: robust to texture, raised by outliers).
// Negative when too few blocks are inside the mask.
double coefficient_noise(const Eigen::MatrixXf& coefficients) {
  if (coefficients.rows() < std::int64_t(min_coefficients)) return -1;
  std::vector<double> per_light(std::size_t(coefficients.cols()));
  std::vector<double> magnitudes(std::size_t(coefficients.rows()));
  for (std::int64_t i = 0; i < coefficients.cols(); ++i) {
    for (std::int64_t b = 0; b < coefficients.rows(); ++b)
      magnitudes[std::size_t(b)] = std::abs(double(coefficients(b, i)));
    per_light[std::size_t(i)] = median(magnitudes) * mad_to_sigma;
  }
  const double spatial = median(per_light);
  const Eigen::MatrixXd covariance =
      (coefficients.transpose() * coefficients).cast<double>() / double(coefficients.rows());
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues();
  std::vector<double> values(eigenvalues.data(), eigenvalues.data() + eigenvalues.size());
  const double over_lights = std::sqrt(std::max(0.0, median(values)));
  return std::min(spatial, over_lights);
}

std::vector<float> channel_noise(const ReflectanceField& field, unsigned threads) {
  const int channels = field.channels;
  std::vector<double> measured(std::size_t(channels), -1.0);
  parallel_for(measured.size(), threads, [&](std::size_t c, unsigned) {
    measured[c] = coefficient_noise(diagonal_coefficients(field, int(c)));
  });
  // Quantized images: the rounding's own noise is the least there is.
  const double quantization = field.noise_floor / std::sqrt(12.0);
  std::vector<float> sigma(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c)
    sigma[std::size_t(c)] = float(std::max(measured[std::size_t(c)], quantization));
  return sigma;
}

// The mean function per channel of the darkest tenth of the pixels inside the mask that are not
// all zero (by their energy over all channels); zeros when there are none.
std::vector<float> dark_shape(const ReflectanceField& field) {
  const int lights = field.lights(), channels = field.channels;
  std::vector<std::pair<double, std::int64_t>> energies;
  for (std::int64_t q = 0; q < field.pixels(); ++q) {
    if (!field.mask.empty() && field.mask[std::size_t(q)] == 0) continue;
    const double energy =
        field.values.middleRows(q * channels, channels).cast<double>().squaredNorm();
    if (std::isfinite(energy) && energy > 0) energies.emplace_back(energy, q);
  }
  std::vector<float> shape(std::size_t(channels) * lights, 0.0f);
  if (energies.empty()) return shape;
  const std::size_t darkest = std::max<std::size_t>(1, energies.size() / 10);
  std::nth_element(energies.begin(), energies.begin() + std::ptrdiff_t(darkest - 1),
                   energies.end());
  std::vector<double> sum(shape.size(), 0.0);
  for (std::size_t k = 0; k < darkest; ++k)
    for (int c = 0; c < channels; ++c)
      for (int i = 0; i < lights; ++i)
        sum[std::size_t(c) * lights + i] += field.values(energies[k].second * channels + c, i);
  for (std::size_t v = 0; v < shape.size(); ++v) shape[v] = float(sum[v] / double(darkest));
  return shape;
}

}  // namespace

NoiseModel estimate_noise(const ReflectanceField& field, unsigned threads) {
  check_finite_values(field);
  NoiseModel model;
  model.sigma = channel_noise(field, threads);
  for (const float sigma : model.sigma) model.threshold.push_back(dark_threshold_sigmas * sigma);
  model.shape = dark_shape(field);
  return model;
}

NoiseModel noise_floor_model(const ReflectanceField& field, float floor) {
  if (!std::isfinite(floor) || floor < 0)
    throw Error("the noise floor must be a finite value >= 0, not " + std::to_string(floor));
  check_finite_values(field);
  NoiseModel model;
  model.estimated = false;
  model.threshold.assign(std::size_t(field.channels), floor);
  model.shape = dark_shape(field);
  return model;
}

NoiseModel estimate_streamed_noise(const ReflectanceField& first_strip, float floor,
                                   unsigned threads) {
  NoiseModel model =
      floor >= 0 ? noise_floor_model(first_strip, floor) : estimate_noise(first_strip, threads);
  model.block_gains = false;
  return model;
}

float default_residual_threshold(const NoiseModel& model, const ReflectanceField& field) {
  if (!model.estimated) return model.threshold.empty() ? 0.0f : model.threshold.front();
  const double mean =
      model.sigma.empty()
          ? 0.0
          : std::accumulate(model.sigma.begin(), model.sigma.end(), 0.0) / model.sigma.size();
  return std::max(residual_threshold_sigmas * float(mean), field.noise_floor);
}

}  // namespace relume
