// relume::compress_file (relume/compress.hpp) is the run `relume compress` makes: for the same
// input and options both write the same container, byte for byte (the command and this test are
// built from one tree, so even the header's software line agrees), on a DiLiGenT crop (8-bit PNG,
// linear by the folder's light_intensities.txt) and on an RTI .lp capture of 8-bit JPEGs (sRGB by
// the input-encoding rule); the report it returns is the command's --report, and a rate target
// gives the command's container.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <relume/compress.hpp>
#include <relume/container.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::TempDir;

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

CompressOptions small_options() {
  CompressOptions options;
  options.clusters = 6;
  options.terms = 3;
  options.residual = ResidualBudget{3};
  options.iterations = 2;
  options.seed = 5;
  options.threads = 2;
  options.assign = "cpu";
  return options;
}

const char* small_flags =
    "--clusters 6 --terms 3 --residual 3 --iterations 2 --seed 5 --threads 2 --assign cpu";

void expect_same_container_as_the_command(const std::filesystem::path& input) {
  TempDir work;
  const testing::CommandResult command = testing::run_relume(
      "-q compress '" + input.string() + "' -o '" + (work / "command.relume").string() + "' " +
      small_flags + " --report '" + (work / "command.json").string() + "'");
  ASSERT_EQ(command.exit_code, 0) << command.output;
  const CompressionReport report =
      compress_file(input.string(), work / "library.relume", small_options());
  EXPECT_EQ(file_bytes(work / "library.relume"), file_bytes(work / "command.relume"));
  EXPECT_EQ(report.bytes, std::filesystem::file_size(work / "library.relume"));

  const auto theirs = nlohmann::json::parse(file_bytes(work / "command.json"));
  const auto ours = nlohmann::json::parse(report.json);
  for (const char* key : {"bytes", "error_all", "error_masked", "bytes_per_pixel", "field"})
    EXPECT_EQ(ours.at(key), theirs.at(key)) << key;
  EXPECT_DOUBLE_EQ(report.error_masked, theirs.at("error_masked").get<double>());
  EXPECT_FALSE(std::filesystem::exists(work / "library.relume.checkpoint"));
}

TEST(CompressFile, WritesTheCommandsContainerForADiligentCrop) {
  RELUME_REQUIRE_SHARED_DATA(data);
  expect_same_container_as_the_command(data / "olat" / "diligent-bear-crop8");
}

TEST(CompressFile, WritesTheCommandsContainerForAnRtiCaptureOfJpegs) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const std::filesystem::path lp = data / "olat" / "rti-loewenkopf" / "dirs.lp";
  expect_same_container_as_the_command(lp);
  // The JPEGs were decoded as sRGB (the rule the command follows): the header says so too.
  TempDir work;
  compress_file(lp.string(), work / "a.relume", small_options());
  CompressOptions linear = small_options();
  linear.input_encoding = "linear";
  compress_file(lp.string(), work / "b.relume", linear);
  EXPECT_NE(file_bytes(work / "a.relume"), file_bytes(work / "b.relume"));
}

TEST(CompressFile, MeetsARateTargetAsTheCommandDoes) {
  TempDir work;
  const std::string scene = (work / "scene").string();
  ASSERT_EQ(testing::run_relume("-q synth -o '" + scene +
                                "' --size 24x20 --lights 40 --samples 1 --threads 2")
                .exit_code,
            0);
  const testing::CommandResult command =
      testing::run_relume("-q compress '" + scene + "' -o '" + (work / "command.relume").string() +
                          "' --threads 2 --assign cpu --target-bytes-per-pixel 30");
  ASSERT_EQ(command.exit_code, 0) << command.output;
  CompressOptions options;
  options.threads = 2;
  options.assign = "cpu";
  options.target_bytes_per_pixel = 30;
  const CompressionReport report = compress_file(scene, work / "target.relume", options);
  EXPECT_EQ(file_bytes(work / "target.relume"), file_bytes(work / "command.relume"));
  const auto search = nlohmann::json::parse(report.json).at("rate_target");
  EXPECT_TRUE(search.at("met").get<bool>());
  EXPECT_LE(report.bytes, std::uint64_t(30 * 24 * 20));
  EXPECT_GT(report.bytes, std::uint64_t(0.9 * 30 * 24 * 20));
  EXPECT_NE(report.summary.find("target.relume"), std::string::npos);
}

TEST(CompressFile, RefusesBadOptionsBeforeAnyWork) {
  TempDir work;
  CompressOptions options;
  options.transform = "wavelet";
  EXPECT_EQ(testing::error_message([&] { compress_file("missing", work / "x.relume", options); }),
            "--transform must be 'identity' or 'haar', got 'wavelet'");
  options = {};
  options.target_bytes_per_pixel = 1;
  options.target_psnr = 40;
  EXPECT_EQ(testing::error_message([&] { compress_file("missing", work / "x.relume", options); }),
            "--target-bytes-per-pixel and --target-psnr are two targets: give one");
}

}  // namespace
}  // namespace relume
