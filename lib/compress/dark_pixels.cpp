// Implementation of the dark pixel selection (see dark_pixels.hpp).
#include "compress/dark_pixels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"
#include "model/dark_gains.hpp"

namespace relume {
namespace {

// Rounds of block gains and tests after the first, per-pixel one.
constexpr int block_rounds = 2;
// The gain step is this fraction of the tightest threshold (over the dark shape's RMS): its
// rounding moves a pixel's leftover by at most an eighth of the threshold.
constexpr double gain_step_of_threshold = 0.25;

// What the test needs of one channel of one pixel: its energy and its product with the shape.
struct Projection {
  double energy = 0, dot = 0;
};

}  // namespace

DarkPixels select_dark_pixels(const ReflectanceField& field, const NoiseModel& noise,
                              unsigned threads) {
  DarkPixels dark;
  const int lights = field.lights(), channels = field.channels;
  if (noise.threshold.empty() ||
      std::any_of(noise.threshold.begin(), noise.threshold.end(), [](float t) { return t <= 0; }))
    return dark;
  std::vector<double> shape_energy(std::size_t(channels), 0.0);
  double step = std::numeric_limits<double>::infinity();
  for (int c = 0; c < channels; ++c) {
    for (int i = 0; i < lights; ++i)
      shape_energy[c] += double(noise.shape[std::size_t(c) * lights + i]) *
                         noise.shape[std::size_t(c) * lights + i];
    if (shape_energy[c] > 0)
      step = std::min(
          step, gain_step_of_threshold * noise.threshold[c] / std::sqrt(shape_energy[c] / lights));
  }
  if (!std::isfinite(step)) step = 1;  // no shape: every gain is 0
  dark.gain_step = float(step);

  const std::int64_t pixels = field.pixels();
  std::vector<Projection> projections(std::size_t(pixels) * channels);
  std::vector<std::uint8_t> candidate(std::size_t(pixels), 0);
  std::vector<float> gains(projections.size(), 0.0f);
  // A channel passes with gain g when the RMS of R - g s over the lights is within its threshold.
  const auto passes = [&](std::int64_t q, int c, double gain) {
    const Projection& p = projections[std::size_t(q) * channels + c];
    const double leftover = p.energy - 2 * gain * p.dot + gain * gain * shape_energy[c];
    const double threshold = noise.threshold[c];
    return leftover <= threshold * threshold * lights;
  };
  parallel_for(std::size_t(pixels), threads, [&](std::size_t q, unsigned) {
    if (!field.mask.empty() && field.mask[q] == 0) return;
    bool dark_pixel = true;
    for (int c = 0; c < channels; ++c) {
      const auto row = field.values.row(std::int64_t(q) * channels + c);
      const float* shape = noise.shape.data() + std::size_t(c) * lights;
      Projection& p = projections[q * channels + c];
      for (int i = 0; i < lights; ++i) {
        p.energy += double(row[i]) * row[i];
        p.dot += double(row[i]) * shape[i];
      }
      const double gain = shape_energy[c] > 0 ? std::max(0.0, p.dot / shape_energy[c]) : 0.0;
      gains[q * channels + c] = float(gain);
      dark_pixel = dark_pixel && passes(std::int64_t(q), c, gain);
    }
    candidate[q] = dark_pixel;
  });

  if (!noise.block_gains) {
    for (std::int64_t q = 0; q < pixels; ++q) {
      bool dark_pixel = candidate[std::size_t(q)] != 0;
      for (int c = 0; c < channels && dark_pixel; ++c) dark_pixel = passes(q, c, 1.0);
      if (dark_pixel) dark.pixels.push_back(std::uint32_t(q));
    }
    dark.gain_step = 0;
    return dark;
  }
  DarkGainGrid grid = empty_dark_gain_grid(field.width, field.height, channels);
  const std::size_t plane = std::size_t(grid.columns) * grid.rows;
  std::vector<std::vector<std::uint32_t>> members(plane);
  for (std::int64_t q = 0; q < pixels; ++q)
    if (candidate[std::size_t(q)])
      members[dark_gain_block_index(grid, field.width, std::uint32_t(q))].push_back(
          std::uint32_t(q));
  for (int round = 0; round < block_rounds; ++round)
    parallel_for(plane, threads, [&](std::size_t block, unsigned) {
      std::vector<std::uint32_t>& inside = members[block];
      if (inside.empty()) return;
      std::vector<float> values(inside.size());
      for (int c = 0; c < channels; ++c) {
        for (std::size_t m = 0; m < inside.size(); ++m)
          values[m] = gains[std::size_t(inside[m]) * channels + c];
        const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
        std::nth_element(values.begin(), middle, values.end());
        grid.values[c * plane + block] =
            std::int32_t(std::min<double>(max_quantized_gain, std::round(double(*middle) / step)));
      }
      std::erase_if(inside, [&](std::uint32_t q) {
        for (int c = 0; c < channels; ++c)
          if (!passes(q, c, double(float(grid.values[c * plane + block] * dark.gain_step))))
            return true;
        return false;
      });
    });
  for (std::int64_t q = 0; q < pixels; ++q) candidate[std::size_t(q)] = 0;
  for (const auto& inside : members)
    for (const std::uint32_t q : inside) candidate[q] = 1;
  for (std::int64_t q = 0; q < pixels; ++q) {
    if (!candidate[std::size_t(q)]) continue;
    dark.pixels.push_back(std::uint32_t(q));
    const std::size_t block = dark_gain_block_index(grid, field.width, std::uint32_t(q));
    for (int c = 0; c < channels; ++c)
      dark.gains.push_back(float(grid.values[c * plane + block] * dark.gain_step));
  }
  return dark;
}

}  // namespace relume
