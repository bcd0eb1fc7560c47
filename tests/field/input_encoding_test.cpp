// Tests of the input-encoding rule (field/input_encoding.hpp) on files written here through
// OpenImageIO and on the real captures: 8-bit PNG and JPEG sRGB unless tagged linear or in a
// DiLiGenT folder, 16-bit and float linear, explicit requests taken as they are, the values
// load_field gives under each decision, and read_image's own automatic choice.
#include "field/input_encoding.hpp"

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <relume/field.hpp>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {
using ::testing::HasSubstr;
using testing::TempDir;
namespace fs = std::filesystem;

// A one-light folder holding `file`, a 1x1 grey image of `value` in `format`, with an optional
// colour-space attribute and an optional light_intensities.txt.
fs::path one_image_field(const fs::path& dir, const std::string& file, OIIO::TypeDesc format,
                         float value, const std::string& color_space = "",
                         bool intensities = false) {
  fs::create_directories(dir);
  std::ofstream(dir / "light_directions.txt") << "0 0 1\n";
  std::ofstream(dir / "filenames.txt") << file << "\n";
  if (intensities) std::ofstream(dir / "light_intensities.txt") << "1 1 1\n";
  auto out = OIIO::ImageOutput::create((dir / file).string());
  OIIO::ImageSpec spec(1, 1, 1, format);
  if (!color_space.empty()) spec.attribute("oiio:ColorSpace", color_space);
  EXPECT_TRUE(out->open((dir / file).string(), spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, &value));
  out->close();
  return dir;
}

constexpr float grey = 128.0f / 255.0f;
constexpr float grey_decoded = 0.2158605f;  // srgb_to_linear(128 / 255)

TEST(InputEncoding, EightBitPngIsSrgbUnlessTaggedLinearOrInADiligentFolder) {
  TempDir dir;
  const fs::path plain = one_image_field(dir / "plain", "1.png", OIIO::TypeDesc::UINT8, grey);
  const InputEncodingDecision automatic = decide_input_encoding(plain, EightBitEncoding::automatic);
  EXPECT_EQ(automatic.encoding, EightBitEncoding::srgb);
  EXPECT_THAT(automatic.reason, HasSubstr("8-bit png"));
  EXPECT_THAT(automatic.reason, HasSubstr("decoded as sRGB"));
  EXPECT_NEAR(load_field(plain).values(0, 0), grey_decoded, 1e-6);

  const fs::path tagged =
      one_image_field(dir / "tagged", "1.png", OIIO::TypeDesc::UINT8, grey, "linear");
  EXPECT_EQ(decide_input_encoding(tagged, EightBitEncoding::automatic).encoding,
            EightBitEncoding::linear);
  EXPECT_FLOAT_EQ(load_field(tagged).values(0, 0), grey);

  const fs::path diligent =
      one_image_field(dir / "diligent", "1.png", OIIO::TypeDesc::UINT8, grey, "", true);
  const InputEncodingDecision linear = decide_input_encoding(diligent, EightBitEncoding::automatic);
  EXPECT_EQ(linear.encoding, EightBitEncoding::linear);
  EXPECT_THAT(linear.reason, HasSubstr("DiLiGenT"));
  EXPECT_FLOAT_EQ(load_field(diligent).values(0, 0), grey);
}

TEST(InputEncoding, JpegIsSrgbAndSixteenBitAndFloatAreLinear) {
  TempDir dir;
  const fs::path jpeg = one_image_field(dir / "jpeg", "1.jpg", OIIO::TypeDesc::UINT8, grey);
  EXPECT_EQ(decide_input_encoding(jpeg, EightBitEncoding::automatic).encoding,
            EightBitEncoding::srgb);
  const fs::path sixteen = one_image_field(dir / "16", "1.png", OIIO::TypeDesc::UINT16, 0.5f);
  const InputEncodingDecision deep = decide_input_encoding(sixteen, EightBitEncoding::automatic);
  EXPECT_EQ(deep.encoding, EightBitEncoding::linear);
  EXPECT_THAT(deep.reason, HasSubstr("16-bit png"));
  EXPECT_NEAR(load_field(sixteen).values(0, 0), 0.5f, 1e-4);
  const fs::path exr = one_image_field(dir / "exr", "1.exr", OIIO::TypeDesc::HALF, 0.5f);
  const InputEncodingDecision floating = decide_input_encoding(exr, EightBitEncoding::automatic);
  EXPECT_EQ(floating.encoding, EightBitEncoding::linear);
  EXPECT_THAT(floating.reason, HasSubstr("floating point"));
  EXPECT_FLOAT_EQ(load_field(exr).values(0, 0), 0.5f);
}

TEST(InputEncoding, ExplicitRequestsAreTakenAsTheyAre) {
  TempDir dir;
  const fs::path plain = one_image_field(dir / "plain", "1.png", OIIO::TypeDesc::UINT8, grey);
  const fs::path diligent =
      one_image_field(dir / "diligent", "1.png", OIIO::TypeDesc::UINT8, grey, "", true);
  EXPECT_EQ(decide_input_encoding(plain, EightBitEncoding::linear).encoding,
            EightBitEncoding::linear);
  EXPECT_EQ(decide_input_encoding(diligent, EightBitEncoding::srgb).encoding,
            EightBitEncoding::srgb);
  FieldLoadOptions linear, srgb;
  linear.image.eight_bit = EightBitEncoding::linear;
  srgb.image.eight_bit = EightBitEncoding::srgb;
  EXPECT_FLOAT_EQ(load_field(plain, linear).values(0, 0), grey);
  EXPECT_NEAR(load_field(diligent, srgb).values(0, 0), grey_decoded, 1e-6);
}

TEST(InputEncoding, ReadImageDecidesPerFileWhenAskedTo) {
  TempDir dir;
  one_image_field(dir / "plain", "1.png", OIIO::TypeDesc::UINT8, grey);
  one_image_field(dir / "tagged", "1.png", OIIO::TypeDesc::UINT8, grey, "linear");
  const ImageReadOptions automatic{EightBitEncoding::automatic};
  EXPECT_NEAR(read_image(dir / "plain/1.png", automatic).pixels[0], grey_decoded, 1e-6);
  EXPECT_FLOAT_EQ(read_image(dir / "tagged/1.png", automatic).pixels[0], grey);
  EXPECT_FLOAT_EQ(read_image(dir / "plain/1.png").pixels[0], grey) << "read_image: linear default";
}

TEST(InputEncoding, RealCapturesAreDecidedAsTheirSourcesSay) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const InputEncodingDecision rti =
      decide_input_encoding(data / "olat/rti-loewenkopf/dirs.lp", EightBitEncoding::automatic);
  EXPECT_EQ(rti.encoding, EightBitEncoding::srgb);
  EXPECT_THAT(rti.reason, HasSubstr("declared sRGB")) << "the JPEGs' Exif ColorSpace is sRGB";
  for (const char* linear : {"olat/diligent-bear-crop8", "olat/diligent-ball-16bit"})
    EXPECT_EQ(decide_input_encoding(data / linear, EightBitEncoding::automatic).encoding,
              EightBitEncoding::linear)
        << linear;
}

}  // namespace
}  // namespace relume
