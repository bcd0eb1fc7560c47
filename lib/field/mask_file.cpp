// Reading object masks.
#include "field/mask_file.hpp"

#include <algorithm>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <string>

namespace relume {

std::vector<std::uint8_t> read_mask(const std::filesystem::path& path, int width, int height) {
  const Image image = read_image(path);
  if (image.width != width || image.height != height)
    throw Error("mask " + path.string() + " is " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " but the images are " + std::to_string(width) +
                "x" + std::to_string(height));
  std::vector<std::uint8_t> mask(std::size_t(width) * height);
  for (std::size_t p = 0; p < mask.size(); ++p) {
    float any = 0;
    for (int c = 0; c < image.channels; ++c)
      any = std::max(any, image.pixels[p * image.channels + c]);
    mask[p] = any > 0 ? 1 : 0;
  }
  return mask;
}

}  // namespace relume
