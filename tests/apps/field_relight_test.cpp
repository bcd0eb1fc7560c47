// The reference relighter against an independent sum over the real DiLiGenT images, through the
// CLI: relight(ball, L) == sum_i L_i * image_i / intensity_i to float precision, everywhere with
// --no-mask and inside mask.png (black outside) by default.
#include <OpenImageIO/imageio.h>

#include <fstream>
#include <random>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

std::vector<float> read_raw(const fs::path& path, OIIO::ImageSpec* spec) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path;
  *spec = in->spec();
  std::vector<float> pixels(std::size_t(spec->width) * spec->height * spec->nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec->nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  return pixels;
}

TEST(FieldRelight, DiligentBallMatchesIndependentSum) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const fs::path ball = data / "olat/diligent-ball-16bit";
  testing::TempDir dir;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<std::array<float, 3>> lights(96);
  {
    std::ofstream out(dir / "L.txt");
    out.precision(9);
    for (auto& l : lights) {
      for (float& v : l) v = uniform(rng);
      out << l[0] << " " << l[1] << " " << l[2] << "\n";
    }
  }
  for (const char* output : {"x.exr", "masked.exr"}) {
    const auto result = testing::run_relume(
        "relight '" + ball.string() + "' --lights '" + (dir / "L.txt").string() + "' -o '" +
        (dir / output).string() + "'" + (output == std::string("x.exr") ? " --no-mask" : ""));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }

  std::vector<std::string> names;
  std::ifstream list(ball / "filenames.txt");
  for (std::string name; list >> name;) names.push_back(name);
  std::vector<std::array<double, 3>> intensity(96);
  std::ifstream intensities(ball / "light_intensities.txt");
  for (auto& row : intensity) intensities >> row[0] >> row[1] >> row[2];
  ASSERT_EQ(names.size(), 96u);

  OIIO::ImageSpec spec;
  std::vector<double> expected;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto image = read_raw(ball / names[i], &spec);
    ASSERT_EQ(spec.format, OIIO::TypeDesc::UINT16);
    expected.resize(image.size(), 0.0);
    for (std::size_t k = 0; k < image.size(); ++k) {
      const int c = static_cast<int>(k % spec.nchannels);
      expected[k] += double(lights[i][c]) * image[k] / intensity[i][c];
    }
  }
  OIIO::ImageSpec out_spec;
  const auto relit = read_raw(dir / "x.exr", &out_spec);
  ASSERT_EQ(relit.size(), expected.size());
  double worst = 0, peak = 0;
  for (std::size_t k = 0; k < relit.size(); ++k) {
    worst =
        std::max(worst, std::abs(relit[k] - expected[k]) / std::max(1e-3, std::abs(expected[k])));
    peak = std::max(peak, expected[k]);
  }
  EXPECT_GT(peak, 1.0) << "the test image is not trivially dark";
  EXPECT_LT(worst, 1e-6) << "relative error against the independent sum";

  OIIO::ImageSpec mask_spec;
  const auto mask = read_raw(ball / "mask.png", &mask_spec);
  const auto masked = read_raw(dir / "masked.exr", &out_spec);
  ASSERT_EQ(masked.size(), relit.size());
  std::size_t outside = 0;
  for (std::size_t k = 0; k < masked.size(); ++k) {
    const std::size_t pixel = k / out_spec.nchannels;
    const bool inside = mask[pixel * mask_spec.nchannels] > 0;
    outside += !inside;
    EXPECT_EQ(masked[k], inside ? relit[k] : 0.0f) << "value " << k;
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(outside, relit.size() / 2) << "the ball's mask leaves most of the frame out";
}

}  // namespace
}  // namespace relume
