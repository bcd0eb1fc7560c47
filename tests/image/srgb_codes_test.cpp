// Tests of the 8-bit sRGB table (image/srgb_codes.hpp): it gives the code OpenImageIO stores for
// linear_to_srgb(v), for floats spread over [0, 1] and for every float around every step of the
// code, and an 8-bit PNG written through it decodes to the values the curve written as floats
// (OpenImageIO converting them) gives. NaN and Inf give the end codes, and writes refuse
// exposures beyond 40 stops.
#include "image/srgb_codes.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

int curve_code(float v) {
  const float encoded = linear_to_srgb(std::clamp(v, 0.0f, 1.0f));
  std::uint8_t code = 0;
  OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, &encoded, OIIO::TypeDesc::UINT8, &code, 1);
  return code;
}

TEST(SrgbCodes, EqualTheCurveEverywhereItSteps) {
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f), stride = 4099;
  int steps = 0;
  std::size_t mismatches = 0;
  int previous = curve_code(0.0f);
  for (std::uint32_t bits = stride; bits <= one + stride; bits += stride) {
    const std::uint32_t end = std::min(bits, one);
    const int code = curve_code(std::bit_cast<float>(end));
    mismatches += srgb_code(std::bit_cast<float>(end)) != code;
    if (code != previous) {
      // Every float of the gap in which the code stepped.
      for (std::uint32_t b = end - stride; b <= end; ++b)
        mismatches += srgb_code(std::bit_cast<float>(b)) != curve_code(std::bit_cast<float>(b));
      steps += code - previous;
      previous = code;
    }
  }
  EXPECT_EQ(steps, 255);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(srgb_code(-3.0f), 0);
  EXPECT_EQ(srgb_code(7.5f), 255);
}

// 0 x 2^128 is NaN: the table once took it for a bin index (a crash under --exposure 128).
TEST(SrgbCodes, NonFiniteValuesGiveTheEndCodesInsteadOfAnIndexFromNothing) {
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(srgb_code(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(srgb_code(-std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(srgb_code(-inf), 0);
  EXPECT_EQ(srgb_code(inf), 255);
  EXPECT_EQ(srgb_code(0.0f * inf), 0);
  EXPECT_EQ(unit_clamped(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_EQ(unit_clamped(inf), 1.0f);
  EXPECT_EQ(unit_clamped(0.25f), 0.25f);
}

// A black pixel under an exposure of 128 stops (2^128 is Inf in float) wrote NaN codes: such an
// exposure is refused, naming it, in 8 and 16 bits; the largest one allowed writes black as 0.
TEST(SrgbCodes, WritesRefuseExposuresBeyondFortyStopsAndKeepBlackAtTheLimit) {
  const testing::TempDir folder;
  Image image(4, 2, 3);
  image.pixels[5] = 0.5f;
  for (const double exposure : {128.0, -200.0, double(NAN), double(INFINITY)})
    for (const int bits : {8, 16}) {
      try {
        write_image(folder / "x.png", image, {exposure, bits, false});
        ADD_FAILURE() << "exposure " << exposure << " was written";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("exposure"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("out of range (from -40 to 40)"), std::string::npos)
            << e.what();
      }
      EXPECT_FALSE(std::filesystem::exists(folder / "x.png"));
    }
  write_image(folder / "x.png", image, {max_exposure_stops, 8, false});
  const Image written = read_image(folder / "x.png");
  EXPECT_EQ(written.pixels[0], 0.0f);
  EXPECT_EQ(written.pixels[5], 1.0f);
}

TEST(SrgbCodes, APngThroughTheTableDecodesAsTheCurveWrittenAsFloats) {
  const testing::TempDir folder;
  Image image(256, 64, 1);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = float(i) / float(image.pixels.size() - 1);
  write_image(folder / "table.png", image);

  std::vector<float> encoded(image.pixels.size());
  for (std::size_t i = 0; i < encoded.size(); ++i) encoded[i] = linear_to_srgb(image.pixels[i]);
  auto output = OIIO::ImageOutput::create("curve.png");
  ASSERT_TRUE(output);
  const std::string curve_path = (folder / "curve.png").string();
  ASSERT_TRUE(output->open(curve_path, OIIO::ImageSpec(256, 64, 1, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, encoded.data()));
  ASSERT_TRUE(output->close());

  const Image table = read_image(folder / "table.png"), curve = read_image(curve_path);
  ASSERT_EQ(table.pixels.size(), curve.pixels.size());
  EXPECT_TRUE(table.pixels == curve.pixels);
}

}  // namespace
}  // namespace relume
