// The dark gains as the container stores them (compressed_field.hpp): one quantized gain per
// channel for every dark_gain_block x dark_gain_block block of pixels, on a grid over the whole
// frame, channel-major. The compressor makes every dark pixel's gain its block's quantized value,
// so the grid holds them exactly and the container round-trips them bit for bit.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// The largest magnitude of a quantized gain (16-bit storage).
inline constexpr std::int32_t max_quantized_gain = 32767;

struct DarkGainGrid {
  int columns = 0, rows = 0, channels = 0;
  // (c * rows + by) * columns + bx; 0 in blocks without dark pixels
  std::vector<std::int32_t> values;
};

// The grid's shape for a width x height frame.
DarkGainGrid empty_dark_gain_grid(int width, int height, int channels);

// The block of pixel q (its index on the grid of one channel).
std::size_t dark_gain_block_index(const DarkGainGrid& grid, int width, std::uint32_t q);

// The grid of `field`'s gains: each block's value is its dark pixels' gain / dark_gain_step.
// Throws Error naming the pixel when a block's dark pixels have different gains or a gain is
// not a multiple of the step within the 16-bit range (validate_compressed_field checks this).
DarkGainGrid dark_gain_grid(const CompressedField& field);

// Sets field.dark_gains from the grid (field.dark_pixels, dark_gain_step and the frame's size
// must be set).
void expand_dark_gains(CompressedField& field, const DarkGainGrid& grid);

}  // namespace relume
