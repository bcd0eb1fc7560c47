// Tests for loading reflectance fields: layouts, intensity division, masks, bit depths, and every
// kind of bad input (each named in the message, each a non-zero exit from the CLI).
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "field/downsample.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
using testing::TempDir;
namespace fs = std::filesystem;

Image gradient_image(int w, int h, int channels, float scale) {
  Image image(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) image.at(x, y, c) = scale * (1 + x + 10 * y + 100 * c);
  return image;
}

// A three-light DiLiGenT-style folder of 4x3 EXR images.
void write_small_folder(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "filenames.txt") << "a.exr\nb.exr\nc.exr\n";
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n1 0 0\n0 1 0\n";
  std::ofstream(dir / "light_intensities.txt") << "1 1 1\n2 4 8\n0.5 0.5 0.5\n";
  write_image(dir / "a.exr", gradient_image(4, 3, 3, 1));
  write_image(dir / "b.exr", gradient_image(4, 3, 3, 2));
  write_image(dir / "c.exr", gradient_image(4, 3, 3, 3));
}

std::string load_error(const fs::path& path) {
  return testing::error_message([&] { load_field(path); });
}

TEST(FieldIo, LoadsFolderAndDividesByIntensity) {
  TempDir dir;
  write_small_folder(dir.path());
  const ReflectanceField field = load_field(dir.path());
  EXPECT_EQ(field.width, 4);
  EXPECT_EQ(field.height, 3);
  EXPECT_EQ(field.channels, 3);
  EXPECT_EQ(field.lights(), 3);
  // Pixel (1, 2), channel 2: raw value scale * (1 + 1 + 20 + 200) = 222 * scale.
  const auto p = field.function_index(1, 2, 2);
  EXPECT_FLOAT_EQ(field.values(p, 0), 222.0f);
  EXPECT_FLOAT_EQ(field.values(p, 1), 2 * 222.0f / 8);
  EXPECT_FLOAT_EQ(field.values(p, 2), 3 * 222.0f / 0.5f);
  EXPECT_EQ(field.mask, std::vector<std::uint8_t>(12, 1));
}

// Without filenames.txt the numbered images are the lights in the order of their numbers, with or
// without leading zeros: 2.exr is light 2, before 10.exr.
TEST(FieldIo, NumberedImagesAreTakenInNumericOrder) {
  TempDir dir;
  const int lights = 12;
  std::ofstream directions(dir / "light_directions.txt");
  for (int i = 1; i <= lights; ++i) {
    directions << "0 0 1\n";
    const std::string name = i == 3 ? "003.exr" : std::to_string(i) + ".exr";
    write_image(dir / name, gradient_image(4, 3, 1, float(i)));
  }
  directions.close();
  const ReflectanceField field = load_field(dir.path());
  ASSERT_EQ(field.lights(), lights);
  for (int i = 0; i < lights; ++i) {
    EXPECT_FLOAT_EQ(field.values(0, i), float(i + 1)) << "light " << i;  // pixel (0, 0): 1 x scale
    EXPECT_EQ(field.image_names[i], i == 2 ? "003.exr" : std::to_string(i + 1) + ".exr");
  }
}

TEST(FieldIo, WriteFolderRoundTripsExactly) {
  TempDir dir;
  write_small_folder(dir / "in");
  const ReflectanceField field = load_field(dir / "in");
  ReflectanceField masked = field;
  masked.mask[5] = 0;
  write_field_folder(dir / "out", masked);
  const ReflectanceField back = load_field(dir / "out");
  EXPECT_EQ(back.values, masked.values);
  EXPECT_EQ(back.mask, masked.mask);
  EXPECT_TRUE(back.directions.isApprox(masked.directions));
  EXPECT_EQ(back.intensities, masked.intensities);
}

TEST(FieldIo, SixteenBitPngIsReadAtSixteenBits) {
  TempDir dir;
  fs::create_directories(dir / "f");
  std::ofstream(dir / "f/light_directions.txt") << "0 0 1\n";
  const std::uint16_t values[2] = {1, 65535};
  auto out = OIIO::ImageOutput::create((dir / "f/001.png").string());
  ASSERT_TRUE(
      out->open((dir / "f/001.png").string(), OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::UINT16)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, values));
  out->close();
  const ReflectanceField field = load_field(dir / "f");
  EXPECT_EQ(field.channels, 1);
  EXPECT_FLOAT_EQ(field.values(0, 0), 1.0f / 65535.0f);  // an 8-bit read would give 0
  EXPECT_FLOAT_EQ(field.values(1, 0), 1.0f);
}

TEST(FieldIo, RealDiligentAndRtiLoad) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const ReflectanceField bear = load_field(data / "olat/diligent-bear-crop8");
  EXPECT_EQ(bear.width, 244);
  EXPECT_EQ(bear.height, 288);
  EXPECT_EQ(bear.lights(), 96);
  const auto inside = std::count(bear.mask.begin(), bear.mask.end(), 1);
  EXPECT_GT(inside, 1000);
  EXPECT_LT(inside, bear.pixels());
  const ReflectanceField rti = load_field(data / "olat/rti-loewenkopf/dirs.lp");
  EXPECT_EQ(rti.width, 64);
  EXPECT_EQ(rti.height, 43);
  EXPECT_EQ(rti.lights(), 240);
  EXPECT_TRUE(rti.values.allFinite());
  EXPECT_GT(rti.values.maxCoeff(), 0.1f);
}

TEST(FieldIo, DownsampleAveragesBoxesAndKeepsAnyMask) {
  TempDir dir;
  write_small_folder(dir.path());
  ReflectanceField field = load_field(dir.path());
  field.mask.assign(12, 0);
  field.mask[field.width * 1 + 1] = 1;  // pixel (1, 1)
  const ReflectanceField half = downsample_field(field);
  EXPECT_EQ(half.width, 2);
  EXPECT_EQ(half.height, 1);
  const auto expected = 0.25f * (field.values.row(field.function_index(2, 0, 1)) +
                                 field.values.row(field.function_index(3, 0, 1)) +
                                 field.values.row(field.function_index(2, 1, 1)) +
                                 field.values.row(field.function_index(3, 1, 1)));
  EXPECT_TRUE(half.values.row(half.function_index(1, 0, 1)).isApprox(expected));
  EXPECT_EQ(half.mask, (std::vector<std::uint8_t>{1, 0}));
  EXPECT_THROW(downsample_field(field, 2), Error);  // 2x1 cannot be halved again
}

TEST(FieldIoBadInput, MissingImage) {
  TempDir dir;
  write_small_folder(dir.path());
  fs::remove(dir / "b.exr");
  EXPECT_THAT(load_error(dir.path()),
              ::testing::AllOf(::testing::HasSubstr("b.exr"), ::testing::HasSubstr("not found")));
}

TEST(FieldIoBadInput, ImagesOfDifferentSizeOrChannels) {
  TempDir dir;
  write_small_folder(dir.path());
  write_image(dir / "c.exr", gradient_image(5, 3, 3, 1));
  EXPECT_THAT(load_error(dir.path()),
              ::testing::AllOf(::testing::HasSubstr("c.exr is 5x3"), ::testing::HasSubstr("4x3")));
  write_image(dir / "c.exr", gradient_image(4, 3, 1, 1));
  EXPECT_THAT(load_error(dir.path()), ::testing::AllOf(::testing::HasSubstr("c.exr has 1 channels"),
                                                       ::testing::HasSubstr("has 3")));
}

TEST(FieldIoBadInput, LightCountDoesNotMatchImages) {
  TempDir dir;
  write_small_folder(dir.path());
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n1 0 0\n";
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("2 light directions but 3 images"));
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n1 0 0\n0 1 0\n";
  std::ofstream(dir / "light_intensities.txt") << "1 1 1\n";
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("1 light intensities but 3 images"));
}

TEST(FieldIoBadInput, BadDirectionsAndIntensities) {
  TempDir dir;
  write_small_folder(dir.path());
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n0 0 0\n0 1 0\n";
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("light_directions.txt:2"));
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n1 0 0\n0 x 0\n";
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("'x' is not a number"));
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n1 0 0\n0 1 0\n";
  std::ofstream(dir / "light_intensities.txt") << "1 1 1\n1 0 1\n1 1 1\n";
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("row 2 has intensity 0"));
}

TEST(FieldIoBadInput, NonFinitePixelIsNamed) {
  TempDir dir;
  write_small_folder(dir.path());
  Image image = gradient_image(4, 3, 3, 1);
  image.at(2, 1, 1) = std::nanf("");
  auto out = OIIO::ImageOutput::create((dir / "b.exr").string());
  ASSERT_TRUE(out->open((dir / "b.exr").string(), OIIO::ImageSpec(4, 3, 3, OIIO::TypeDesc::FLOAT)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
  out->close();
  EXPECT_THAT(load_error(dir.path()), ::testing::AllOf(::testing::HasSubstr("b.exr"),
                                                       ::testing::HasSubstr("pixel (2, 1)")));
}

TEST(FieldIoBadInput, NotAFieldAndUnreadableImage) {
  TempDir dir;
  EXPECT_THAT(load_error(dir.path()), ::testing::HasSubstr("is not a reflectance field"));
  EXPECT_THAT(load_error(dir / "nowhere"), ::testing::HasSubstr("not found"));
  write_small_folder(dir / "f");
  std::ofstream(dir / "f/a.exr") << "this is not an image";
  EXPECT_THAT(load_error(dir / "f"), ::testing::HasSubstr("a.exr"));
}

TEST(FieldIoBadInput, CliExitsNonZeroAndWritesNothing) {
  TempDir dir;
  write_small_folder(dir / "f");
  std::ofstream(dir / "f/light_directions.txt") << "0 0 1\n1 0 0\n";
  std::ofstream(dir / "l.txt") << "1 1 1\n1 1 1\n1 1 1\n";
  const auto result =
      testing::run_relume("relight '" + (dir / "f").string() + "' --lights '" +
                          (dir / "l.txt").string() + "' -o '" + (dir / "out.exr").string() + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.output, ::testing::HasSubstr("2 light directions but 3 images"));
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  std::vector<fs::path> left;
  for (const auto& entry : fs::directory_iterator(dir.path())) left.push_back(entry.path());
  EXPECT_EQ(left.size(), 2u) << "no temporary files are left behind";
}

}  // namespace
}  // namespace relume
