// Tests of encoding images into memory (image/image_bytes.hpp), as `relume view` sends frames:
// the bytes are those write_image puts in a file of the same format and options, and the same
// inputs are refused.
#include "image/image_bytes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

Image gradient() {
  Image image(37, 23, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = float(i % 101) / 60.0f;  // up to 1.67: some values clip when exposed
  return image;
}

TEST(ImageBytes, EqualTheFileWriteImageWrites) {
  const testing::TempDir folder;
  const Image image = gradient();
  const std::vector<std::pair<std::string, ImageWriteOptions>> cases = {
      {".png", {0.5, 0, false}}, {".png", {-1, 16, false}}, {".jpg", {0, 0, false}},
      {".exr", {0, 0, false}},   {".exr", {0, 0, true}},
  };
  for (const auto& [extension, options] : cases) {
    const std::filesystem::path file = folder / ("written" + extension);
    std::filesystem::remove(file);
    write_image(file, image, options);
    const std::string bytes = encode_image_bytes(extension, image, options);
    EXPECT_GT(bytes.size(), 100u) << extension;
    EXPECT_TRUE(bytes == file_bytes(file))
        << extension << " bits " << options.bits << " half " << options.half;
  }
}

TEST(ImageBytes, RefusesWhatWriteImageRefuses) {
  Image image = gradient();
  EXPECT_THAT(testing::error_message([&] {
                encode_image_bytes(".jpg", image, {0, 16, false});
              }),
              ::testing::HasSubstr("JPEG holds 8 bits"));
  image.at(4, 2, 1) = NAN;
  EXPECT_THAT(testing::error_message([&] { encode_image_bytes(".png", image); }),
              ::testing::HasSubstr("pixel (4, 2) channel 1"));
}

}  // namespace
}  // namespace relume
