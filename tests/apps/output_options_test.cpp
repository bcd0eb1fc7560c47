// Tests of how the commands write their outputs, run as commands on a small synthetic scene:
// nothing is overwritten silently (-y/--overwrite, before or after the command's name; decompress
// refuses a non-empty folder; outputs are checked before any work), a batch compress refuses
// inputs whose containers would collide, PNG/TIFF at 8 or 16 bits and EXR at half or float,
// --exposure auto (and any exposure noted as unused for floats), and frame patterns with %d or #### from --start-number.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <relume/image.hpp>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

class OutputOptions : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    run_or_fail("synth -o '" + path("scene") + "' --size 16x12 --lights 20 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
                "' --clusters 2 --terms 2 --residual 3");
    std::ofstream lights(path("lights.txt"));
    for (int i = 0; i < 20; ++i) lights << "1 1 1\n";
  }

  static std::string relight_to(const std::string& output) {
    return "relight '" + path("scene.relume") + "' --lights '" + path("lights.txt") + "' -o '" +
           path(output) + "'";
  }
};

TEST_F(OutputOptions, AnExistingOutputIsReplacedOnlyWithOverwrite) {
  write_file_atomically(path("taken.exr"), "not an image");
  const auto refused = testing::run_relume(relight_to("taken.exr"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("taken.exr exists: pass -y/--overwrite"), std::string::npos)
      << refused.output;
  EXPECT_EQ(read_file(path("taken.exr")), "not an image");

  run_or_fail("-y " + relight_to("taken.exr"));
  EXPECT_EQ(read_image(path("taken.exr")).width, 16);
  run_or_fail(relight_to("taken.exr") + " --overwrite");  // after the command's name too

  // lights, sky and compare --json refuse the same way.
  for (const std::string& command :
       {"lights --dirs '" + path("scene") + "' --light-dir 0,0,1 -o '" + path("taken.exr") + "'",
        "sky -o '" + path("taken.exr") + "'",
        "compare '" + path("taken.exr") + "' '" + path("taken.exr") + "' --json '" +
            path("taken.exr") + "'"}) {
    const auto result = testing::run_relume(command);
    EXPECT_EQ(result.exit_code, 1) << command;
    EXPECT_NE(result.output.find("exists"), std::string::npos) << command << result.output;
  }
}

TEST_F(OutputOptions, DecompressRefusesANonEmptyFolder) {
  fs::create_directories(path("empty"));
  run_or_fail("decompress '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  const auto refused =
      testing::run_relume("decompress '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("not empty"), std::string::npos) << refused.output;
  run_or_fail("decompress -y '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  EXPECT_TRUE(fs::exists(path("empty/filenames.txt")));
  const auto synth =
      testing::run_relume("synth -o '" + path("empty") + "' --size 4x4 --lights 4 --samples 1");
  EXPECT_EQ(synth.exit_code, 1) << synth.output;
}

TEST_F(OutputOptions, OutputsAreCheckedBeforeAnyWork) {
  // compress: the existing container is refused before the field loads.
  const auto compress = testing::run_relume("compress '" + path("scene") + "' -o '" +
                                            path("scene.relume") + "' --clusters 2 --terms 2");
  EXPECT_EQ(compress.exit_code, 1);
  EXPECT_NE(compress.output.find("scene.relume exists"), std::string::npos) << compress.output;
  EXPECT_EQ(compress.output.find("loaded"), std::string::npos) << compress.output;
  // relight-sequence: one existing frame, and no frame is written.
  fs::create_directories(path("frames"));
  write_file_atomically(path("frames/0001.exr"), "taken");
  const auto sequence =
      testing::run_relume("relight-sequence '" + path("scene.relume") +
                          "' --light-orbit 30 --frames 3 -o '" + path("frames/%04d.exr") + "'");
  EXPECT_EQ(sequence.exit_code, 1);
  EXPECT_NE(sequence.output.find("0001.exr exists"), std::string::npos) << sequence.output;
  EXPECT_FALSE(fs::exists(path("frames/0000.exr")));
}

TEST_F(OutputOptions, ABatchCompressRefusesCollidingNames) {
  fs::create_directories(path("a"));
  fs::create_directories(path("b"));
  fs::copy(path("scene"), path("a/scene"));
  fs::copy(path("scene"), path("b/scene"));
  const auto result = testing::run_relume("compress '" + path("a/scene") + "' '" + path("b/scene") +
                                          "' -o '" + path("batch") + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("would both write"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("batch")));
}

// The type OpenImageIO finds stored in `path`.
OIIO::TypeDesc stored_type(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  return in ? in->spec().format : OIIO::TypeDesc::UNKNOWN;
}

TEST_F(OutputOptions, IntegerOutputsAt8Or16BitsAndExrAtHalfOrFloat) {
  const std::pair<std::string, OIIO::TypeDesc> cases[] = {
      {"eight.png", OIIO::TypeDesc::UINT8},
      {"sixteen.png --bits 16", OIIO::TypeDesc::UINT16},
      {"float.tif", OIIO::TypeDesc::FLOAT},
      {"sixteen.tif --bits 16", OIIO::TypeDesc::UINT16},
      {"eight.tif --bits 8", OIIO::TypeDesc::UINT8},
      {"float.exr", OIIO::TypeDesc::FLOAT},
      {"half.exr --half", OIIO::TypeDesc::HALF}};
  for (const auto& [arguments, type] : cases) {
    const std::string file = arguments.substr(0, arguments.find(' '));
    const std::string extra = arguments.size() > file.size() ? arguments.substr(file.size()) : "";
    run_or_fail(relight_to(file) + extra);
    EXPECT_EQ(stored_type(path(file)), type) << arguments;
  }
  // The 16-bit PNG holds the same picture as the 8-bit one, more finely.
  const Image eight = read_image(path("eight.png")), sixteen = read_image(path("sixteen.png"));
  ASSERT_EQ(eight.pixels.size(), sixteen.pixels.size());
  for (std::size_t i = 0; i < eight.pixels.size(); ++i)
    ASSERT_NEAR(eight.pixels[i], sixteen.pixels[i], 0.5 / 255 + 1e-6) << i;
  // Options that do not fit the format are refused before any work, and nothing is written.
  for (const std::string& bad :
       {relight_to("deep.jpg") + " --bits 16", relight_to("half.png") + " --half",
        relight_to("bits.exr") + " --bits 8"}) {
    const auto result = testing::run_relume(bad);
    EXPECT_EQ(result.exit_code, 1) << bad << "\n" << result.output;
  }
  EXPECT_FALSE(fs::exists(path("deep.jpg")));
  EXPECT_FALSE(fs::exists(path("half.png")));
  EXPECT_EQ(testing::run_relume(relight_to("twelve.png") + " --bits 12").exit_code, 2);
}

// The 99th percentile of the luminance of the lit pixels of a linear image.
double lit_percentile(const Image& image) {
  std::vector<float> lit;
  for (std::size_t p = 0; p < image.pixels.size() / image.channels; ++p) {
    const float* v = &image.pixels[p * image.channels];
    const float y = 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2];
    if (y > 0) lit.push_back(y);
  }
  EXPECT_GT(lit.size(), 20u);
  const auto at = lit.begin() + std::ptrdiff_t(0.99 * double(lit.size() - 1));
  std::nth_element(lit.begin(), at, lit.end());
  return *at;
}

// An exposure given for a float output was ignored without a word; it is noted before the work,
// and the floats are written unexposed.
TEST_F(OutputOptions, AnExposureForAFloatOutputIsNotedAndLeavesItUnexposed) {
  const auto exposed = run_or_fail(relight_to("exposed.exr") + " --exposure 2");
  EXPECT_NE(exposed.output.find("--exposure 2 leaves " + path("exposed.exr") +
                                " unexposed: it is written as linear floats (the exposure "
                                "applies to integer outputs: PNG, JPEG, TIFF with --bits)"),
            std::string::npos)
      << exposed.output;
  const auto plain = run_or_fail(relight_to("plain.exr"));
  EXPECT_EQ(plain.output.find("unexposed"), std::string::npos) << plain.output;
  EXPECT_EQ(read_image(path("exposed.exr")).pixels, read_image(path("plain.exr")).pixels);
  EXPECT_EQ(run_or_fail(relight_to("exposed.png") + " --exposure 2").output.find("unexposed"),
            std::string::npos);
}

TEST_F(OutputOptions, AutoExposureMapsTheLitObjectsPercentileToNinetyPercent) {
  run_or_fail(relight_to("linear.exr"));
  const double percentile = lit_percentile(read_image(path("linear.exr")));
  const auto result = run_or_fail(relight_to("auto.png") + " --bits 16 --exposure auto");
  const std::string said = "--exposure auto: ";
  const auto at = result.output.find(said);
  ASSERT_NE(at, std::string::npos) << result.output;
  const double stops = std::stod(result.output.substr(at + said.size()));
  EXPECT_NEAR(stops, std::log2(0.9 / percentile), 0.01) << result.output;
  // The PNG holds the linear image exposed by those stops, sRGB-encoded (clipped at 1).
  const Image linear = read_image(path("linear.exr")), png = read_image(path("auto.png"));
  ASSERT_EQ(linear.pixels.size(), png.pixels.size());
  for (std::size_t i = 0; i < png.pixels.size(); ++i) {
    const float expected =
        linear_to_srgb(std::clamp(float(linear.pixels[i] * std::exp2(stops)), 0.0f, 1.0f));
    ASSERT_NEAR(png.pixels[i], expected, 2e-3) << i;
  }
}

TEST_F(OutputOptions, FramePatternsTakePercentDOrHashesFromTheStartNumber) {
  const std::string sequence =
      "relight-sequence '" + path("scene.relume") + "' --light-orbit 30 --frames 3 ";
  const auto hashes = run_or_fail(sequence + "--start-number 7 --exposure auto -o '" +
                                  path("hashes/####.png") + "'");
  for (const char* name : {"0007.png", "0008.png", "0009.png"})
    EXPECT_TRUE(fs::exists(path("hashes/") + name)) << name;
  EXPECT_FALSE(fs::exists(path("hashes/0010.png")));
  const auto said = hashes.output.find("--exposure auto");
  EXPECT_NE(said, std::string::npos) << hashes.output;
  EXPECT_EQ(hashes.output.find("--exposure auto", said + 1), std::string::npos)
      << "one exposure, from the first frame, for every frame";
  run_or_fail(sequence + "--start-number 98 -o '" + path("plain/f%d.exr") + "'");
  for (const char* name : {"f98.exr", "f99.exr", "f100.exr"})
    EXPECT_TRUE(fs::exists(path("plain/") + name)) << name;
  for (const char* bad : {"bad/%s.png", "bad/%04d-%04d.png", "bad/##-%d.png", "bad/none.png"}) {
    const auto result = testing::run_relume(sequence + "-o '" + path(bad) + "'");
    EXPECT_EQ(result.exit_code, 1) << bad;
    EXPECT_NE(result.output.find("output pattern"), std::string::npos) << result.output;
  }
  EXPECT_FALSE(fs::exists(path("bad")));
}

}  // namespace
}  // namespace relume
