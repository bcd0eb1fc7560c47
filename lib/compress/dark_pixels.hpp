// Which pixels the dark model relights (noise_model.hpp): those whose every channel is, within
// the noise, a multiple of the dark shape. Each pixel's own least-squares multiple ("gain")
// decides first; then every block of dark_gain_block x dark_gain_block pixels takes the median
// gain of its dark pixels, quantized, and each pixel is tested again with its block's gain (twice,
// the median taken over the pixels that passed), so that what the container stores is what
// passed the test.
#pragma once

#include <cstdint>
#include <relume/field.hpp>
#include <vector>

#include "compress/noise_model.hpp"

namespace relume {

struct DarkPixels {
  std::vector<std::uint32_t> pixels;  // ascending
  std::vector<float> gains;           // pixels x channels, multiples of gain_step
  float gain_step = 0;
};

// The dark pixels of `field` inside its mask (none when a channel's threshold is zero). The
// values must be finite (prepare_rows checks them first). Without block gains (NoiseModel::
// block_gains) a pixel is dark when it passes with gain 1, and no gains are returned.
DarkPixels select_dark_pixels(const ReflectanceField& field, const NoiseModel& noise,
                              unsigned threads);

}  // namespace relume
