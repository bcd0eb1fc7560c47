// A float image in memory: interleaved channels, rows top to bottom. The common currency of
// loaders, environment maps, renderers and writers.
#pragma once

#include <cstddef>
#include <vector>

namespace relume {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;  // (y * width + x) * channels + c

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c) {}

  std::size_t index(int x, int y, int c) const {
    return (std::size_t(y) * width + x) * channels + c;
  }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
};

}  // namespace relume
