// Tests of the seam contrast behind `relume compare --model`: about 1 when the relit error does
// not depend on the cluster map, clearly above 1 when it jumps at the clusters' borders, the
// pixels whose channels are split, refused inputs, and the command on a crafted container.
#include "model/seam_contrast.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <relume/container.hpp>
#include <relume/image.hpp>

#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

constexpr int side = 32, block = 8;

// Every function stored; cluster = 8 x 8 block of the pixel (4 x 4 blocks, ids 0..3 repeating),
// shifted by one in channel 1 when `split_green` (then every pixel has its channels in two
// clusters, with the borders in the same places).
CompressedField block_clusters(bool split_green) {
  RandomFieldShape shape;
  shape.width = shape.height = side;
  shape.lights = 4;
  shape.clusters = 4;
  shape.terms = 1;
  shape.residual_per_function = 0;
  CompressedField field = random_compressed_field(shape);
  for (std::size_t row = 0; row < field.stored_rows(); ++row) {
    const std::uint32_t p = field.stored_function[row];
    const int pixel = int(p / 3), channel = int(p % 3);
    const int x = pixel % side, y = pixel / side;
    const int id = (x / block + 2 * (y / block)) % 4;
    field.cluster[row] = std::uint32_t(split_green && channel == 1 ? (id + 1) % 4 : id);
  }
  return field;
}

std::uint32_t cluster_at(const CompressedField& field, int x, int y, int c) {
  const std::uint32_t p = std::uint32_t((y * side + x) * 3 + c);
  return field.cluster[std::size_t(
      std::lower_bound(field.stored_function.begin(), field.stored_function.end(), p) -
      field.stored_function.begin())];
}

// A smooth reference and a relit image = reference + noise (sigma 0.01) + jump x cluster id.
std::pair<Image, Image> relit_pair(const CompressedField& field, double jump) {
  Image reference(side, side, 3), image(side, side, 3);
  std::mt19937 random(3);
  std::normal_distribution<float> noise(0, 0.01f);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < 3; ++c) {
        reference.at(x, y, c) = 0.2f + 0.01f * x + 0.005f * y + 0.1f * c;
        image.at(x, y, c) =
            reference.at(x, y, c) + noise(random) + float(jump * cluster_at(field, x, y, c));
      }
  return {image, reference};
}

TEST(SeamContrast, AboutOneWhenTheErrorIgnoresTheClusters) {
  const CompressedField field = block_clusters(false);
  const auto [image, reference] = relit_pair(field, 0);
  const SeamContrast seams = seam_contrast(image, reference, field);
  ASSERT_TRUE(seams.contrast.has_value());
  EXPECT_NEAR(*seams.contrast, 1, 0.15);
  // Borders at x = 8, 16, 24 and y = 8, 16, 24: 2 x 3 x 32 pairs per channel.
  EXPECT_EQ(seams.border_pairs, 3u * 2 * 3 * side);
  EXPECT_EQ(seams.same_pairs + seams.border_pairs, 3u * 2 * side * (side - 1));
  EXPECT_EQ(seams.compared_border_pairs, seams.border_pairs);
  EXPECT_EQ(seams.pixels_with_every_channel_stored, std::size_t(side) * side);
  EXPECT_EQ(seams.pixels_with_split_channels, 0u);
}

TEST(SeamContrast, WellAboveOneWhenTheErrorJumpsAtBorders) {
  const CompressedField field = block_clusters(true);
  const auto [image, reference] = relit_pair(field, 0.05);
  const SeamContrast seams = seam_contrast(image, reference, field);
  ASSERT_TRUE(seams.contrast.has_value());
  EXPECT_GT(*seams.contrast, 3);
  for (const auto& channel : seams.per_channel) EXPECT_GT(channel.value_or(0), 3);
  EXPECT_EQ(seams.pixels_with_split_channels, std::size_t(side) * side);
}

TEST(SeamContrast, LeavesOutUnstoredFunctionsAndPixelsOutsideTheArea) {
  const CompressedField field = block_clusters(false);
  const auto [image, reference] = relit_pair(field, 0.05);
  // Only the left half (x < 12): borders at x = 8 and at y = 8, 16, 24.
  std::vector<std::uint8_t> left(std::size_t(side) * side, 0);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < 12; ++x) left[std::size_t(y) * side + x] = 1;
  const SeamContrast seams = seam_contrast(image, reference, field, left);
  EXPECT_EQ(seams.border_pairs, 3u * (side + 3 * 12));
  EXPECT_EQ(seams.pixels_with_every_channel_stored, 12u * side);
  // Without stored rows nothing can be compared.
  CompressedField nothing_stored = field;
  nothing_stored.stored_function.clear();
  nothing_stored.cluster.clear();
  const SeamContrast none = seam_contrast(image, reference, nothing_stored);
  EXPECT_FALSE(none.contrast.has_value());
  EXPECT_EQ(none.border_pairs + none.same_pairs, 0u);
}

TEST(SeamContrast, RefusesAModelOfAnotherSize) {
  const CompressedField field = block_clusters(false);
  EXPECT_THAT(testing::error_message([&] {
                seam_contrast(Image(4, 4, 3), Image(4, 4, 3), field, {}, "relit.exr",
                              "reference.exr", "scene.relume");
              }),
              ::testing::AllOf(::testing::HasSubstr("scene.relume is 32x32 with 3 channels"),
                               ::testing::HasSubstr("relit.exr is 4x4")));
}

TEST(CompareCommand, ReportsSeamsSsimAndLitPixelFaultsWithAModel) {
  testing::TempDir dir;
  const CompressedField field = block_clusters(true);
  write_container(dir / "blocks.relume", field);
  const auto [image, reference] = relit_pair(field, 0.05);
  write_image(dir / "relit.exr", image);
  write_image(dir / "reference.exr", reference);
  const auto result = testing::run_command(
      "{ " + std::string(RELUME_BINARY) + " compare '" + (dir / "relit.exr").string() + "' '" +
      (dir / "reference.exr").string() + "' --model '" + (dir / "blocks.relume").string() +
      "' --json - 2>/dev/null; } > '" + (dir / "compare.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream in(dir / "compare.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report["seam_contrast"]["contrast"].get<double>(), 3);
  EXPECT_EQ(report["seam_contrast"]["pixels_with_split_channels"], side * side);
  EXPECT_LT(report["luminance_ssim"]["mean"].get<double>(), 1);
  EXPECT_LE(report["luminance_ssim"]["worst_1_percent"].get<double>(),
            report["luminance_ssim"]["mean"].get<double>());
  EXPECT_EQ(report["lit_pixels"]["lit_pixels"], side * side);
  EXPECT_EQ(report["lit_pixels"]["black_pixels"], 0);
  EXPECT_EQ(report["lit_pixels"]["channel_sum_ratio"].size(), 3u);

  // A model of another size is refused by name.
  write_image(dir / "small.exr", Image(4, 4, 3));
  const auto refused = testing::run_relume("compare '" + (dir / "small.exr").string() + "' '" +
                                           (dir / "small.exr").string() + "' --model '" +
                                           (dir / "blocks.relume").string() + "'");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("blocks.relume is 32x32"), std::string::npos) << refused.output;
}

}  // namespace
}  // namespace relume
