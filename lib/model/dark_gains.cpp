// Implementation of the dark gains' block grid (see dark_gains.hpp).
#include "model/dark_gains.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <string>

namespace relume {

DarkGainGrid empty_dark_gain_grid(int width, int height, int channels) {
  DarkGainGrid grid;
  grid.columns = (width + dark_gain_block - 1) / dark_gain_block;
  grid.rows = (height + dark_gain_block - 1) / dark_gain_block;
  grid.channels = channels;
  grid.values.assign(std::size_t(grid.columns) * grid.rows * channels, 0);
  return grid;
}

std::size_t dark_gain_block_index(const DarkGainGrid& grid, int width, std::uint32_t q) {
  const std::uint32_t x = q % std::uint32_t(width), y = q / std::uint32_t(width);
  return std::size_t(y / dark_gain_block) * grid.columns + x / dark_gain_block;
}

DarkGainGrid dark_gain_grid(const CompressedField& field) {
  DarkGainGrid grid = empty_dark_gain_grid(field.width, field.height, field.channels);
  const std::size_t plane = std::size_t(grid.columns) * grid.rows;
  std::vector<std::uint8_t> seen(plane, 0);
  for (std::size_t d = 0; d < field.dark_pixels.size(); ++d) {
    const std::uint32_t q = field.dark_pixels[d];
    const std::size_t block = dark_gain_block_index(grid, field.width, q);
    for (int c = 0; c < field.channels; ++c) {
      const float gain = dark_gain(field, d, c);
      const double steps = double(gain) / field.dark_gain_step;
      const auto value = std::int32_t(std::lround(steps));
      if (!(std::abs(steps) <= max_quantized_gain) || float(value * field.dark_gain_step) != gain)
        throw Error("dark pixel " + std::to_string(q) + " channel " + std::to_string(c) +
                    ": gain " + std::to_string(gain) + " is not a 16-bit multiple of the step " +
                    std::to_string(field.dark_gain_step));
      std::int32_t& stored = grid.values[std::size_t(c) * plane + block];
      if (seen[block] && stored != value)
        throw Error("dark pixel " + std::to_string(q) + " channel " + std::to_string(c) +
                    ": gain " + std::to_string(gain) + " differs from its block's " +
                    std::to_string(stored * field.dark_gain_step) + " (the gains are stored per " +
                    std::to_string(dark_gain_block) + "x" + std::to_string(dark_gain_block) +
                    " block)");
      stored = value;
    }
    seen[block] = 1;
  }
  return grid;
}

void expand_dark_gains(CompressedField& field, const DarkGainGrid& grid) {
  const std::size_t plane = std::size_t(grid.columns) * grid.rows;
  field.dark_gains.resize(field.dark_pixels.size() * std::size_t(field.channels));
  for (std::size_t d = 0; d < field.dark_pixels.size(); ++d) {
    const std::size_t block = dark_gain_block_index(grid, field.width, field.dark_pixels[d]);
    for (int c = 0; c < field.channels; ++c)
      field.dark_gains[d * field.channels + c] =
          float(grid.values[std::size_t(c) * plane + block] * field.dark_gain_step);
  }
}

}  // namespace relume
