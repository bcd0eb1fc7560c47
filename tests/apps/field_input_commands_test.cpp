// Tests of how the commands read an uncompressed field, run as commands on a small synthetic
// scene: masks mean the same everywhere (relight of a folder applies its mask.png, --no-mask keeps
// the background, --mask FILE works for folders and .lp captures in compress and relight,
// compare --mask compares inside only), and compress's summary line leads with the error over
// what is stored, the input encoding is decided once and said, and an image given as the field is
// named as one.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <relume/image.hpp>

#include "field/light_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;
constexpr int width = 24, height = 20, lights = 30;

// The sum of squares of the pixels with x in [x_begin, x_end).
double energy_in_columns(const Image& image, int x_begin, int x_end) {
  double energy = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = x_begin; x < x_end; ++x)
      for (int c = 0; c < image.channels; ++c) energy += std::pow(image.at(x, y, c), 2);
  return energy;
}

class FieldInputCommands : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    run_or_fail("synth -o '" + path("scene") + "' --size 24x20 --lights 30 --samples 1");
    // The whole frame is inside the scene's own mask, the left half inside left.png.
    Image all(width, height, 1), left(width, height, 1);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) all.at(x, y, 0) = 1, left.at(x, y, 0) = x < width / 2;
    write_image(path("scene/mask.png"), all);
    write_image(path("left.png"), left);
    // The same images as an RTI .lp capture beside the folder.
    const LightDirections directions = read_light_directions(path("scene"));
    std::ifstream names(path("scene/filenames.txt"));
    std::ofstream lp(path("scene/capture.lp"));
    lp << lights << '\n';
    for (int i = 0; i < lights; ++i) {
      std::string name;
      std::getline(names, name);
      lp << name << ' ' << directions(i, 0) << ' ' << directions(i, 1) << ' ' << directions(i, 2)
         << '\n';
    }
    std::ofstream sun(path("lights.txt"));
    for (int i = 0; i < lights; ++i) sun << "1 0.8 0.6\n";
  }

  static Image relight(const std::string& input, const std::string& extra,
                       const std::string& output) {
    run_or_fail("-y relight '" + input + "' --lights '" + path("lights.txt") + "' " + extra +
                " -o '" + path(output) + "'");
    return read_image(path(output));
  }
  static nlohmann::json read_json(const std::string& name) {
    std::ifstream in(path(name));
    return nlohmann::json::parse(in);
  }
};

TEST_F(FieldInputCommands, RelightOfAFolderAppliesItsMaskUnlessToldNot) {
  fs::create_directories(path("masked"));
  for (const auto& entry : fs::directory_iterator(path("scene")))
    if (entry.path().filename() != "mask.png" && entry.path().extension() != ".lp")
      fs::copy_file(entry.path(), path("masked") / entry.path().filename());
  fs::copy_file(path("left.png"), path("masked/mask.png"));

  const Image masked = relight(path("masked"), "", "masked.exr");
  const Image kept = relight(path("masked"), "--no-mask", "kept.exr");
  EXPECT_EQ(energy_in_columns(masked, width / 2, width), 0) << "black outside the mask";
  EXPECT_GT(energy_in_columns(kept, width / 2, width), 0) << "--no-mask keeps the background";
  EXPECT_EQ(energy_in_columns(masked, 0, width / 2), energy_in_columns(kept, 0, width / 2));
  EXPECT_GT(energy_in_columns(masked, 0, width / 2), 0);
  // --mask FILE on a folder replaces its mask.png.
  const Image replaced =
      relight(path("scene"), "--mask '" + path("left.png") + "'", "replaced.exr");
  EXPECT_EQ(energy_in_columns(replaced, width / 2, width), 0);
  EXPECT_EQ(energy_in_columns(replaced, 0, width / 2), energy_in_columns(kept, 0, width / 2));
}

TEST_F(FieldInputCommands, CompressAndRelightTakeAMaskForAnLpCapture) {
  run_or_fail("compress '" + path("scene/capture.lp") + "' --mask '" + path("left.png") + "' -o '" +
              path("lp.relume") + "' --clusters 3 --terms 2 --residual 4 --report '" +
              path("lp.json") + "'");
  const nlohmann::json report = read_json("lp.json");
  EXPECT_EQ(report["field"]["outside_mask"], width / 2 * height * 3);
  EXPECT_LE(report["field"]["stored_rows"].get<int>(), width / 2 * height * 3);
  const Image relit = relight(path("lp.relume"), "", "lp.exr");
  EXPECT_EQ(energy_in_columns(relit, width / 2, width), 0);
  EXPECT_GT(energy_in_columns(relit, 0, width / 2), 0);

  // The container cannot give back a background it does not store.
  const auto refused =
      testing::run_relume("relight '" + path("lp.relume") + "' --lights '" + path("lights.txt") +
                          "' --no-mask -o '" + path("refused.exr") + "'");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("--no-mask"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(path("refused.exr")));

  // --mask FILE on a container's relight blacks out what lies outside it.
  run_or_fail("compress '" + path("scene") + "' -o '" + path("all.relume") +
              "' --clusters 3 --terms 2 --residual 4");
  const Image whole = relight(path("all.relume"), "", "whole.exr");
  const Image left = relight(path("all.relume"), "--mask '" + path("left.png") + "'", "left.exr");
  EXPECT_GT(energy_in_columns(whole, width / 2, width), 0);
  EXPECT_EQ(energy_in_columns(left, width / 2, width), 0);
  EXPECT_EQ(energy_in_columns(left, 0, width / 2), energy_in_columns(whole, 0, width / 2));

  const auto missing = testing::run_relume("compress '" + path("scene") + "' --mask '" +
                                           path("none.png") + "' -o '" + path("none.relume") + "'");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("none.png"), std::string::npos) << missing.output;
}

// The %.5f the summary line prints for a report value.
std::string five_digits(const nlohmann::json& value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5f", value.get<double>());
  return text;
}

TEST_F(FieldInputCommands, CompressSummaryLeadsWithTheErrorOverWhatIsStored) {
  const auto masked =
      run_or_fail("compress '" + path("scene") + "' --mask '" + path("left.png") + "' -o '" +
                  path("summary.relume") + "' --clusters 3 --terms 2 --residual 4 --report '" +
                  path("summary.json") + "'");
  const nlohmann::json report = read_json("summary.json");
  ASSERT_GT(report["error_all"].get<double>(), 0.3) << "the unstored half counts as lost";
  EXPECT_LT(report["error_masked"].get<double>(), 0.1);
  EXPECT_NE(masked.output.find("bytes ("), std::string::npos) << masked.output;
  const std::string lead =
      "error " + five_digits(report["error_masked"]) + " over the stored object";
  EXPECT_NE(masked.output.find(lead), std::string::npos) << masked.output;
  EXPECT_NE(masked.output.find("whole frame " + five_digits(report["error_all"])),
            std::string::npos)
      << masked.output;
  EXPECT_LT(masked.output.find(lead), masked.output.find("whole frame")) << masked.output;

  // Without a mask there is one error, over everything.
  const auto unmasked = run_or_fail(
      "compress '" + path("scene") + "' -o '" + path("summary-all.relume") +
      "' --clusters 3 --terms 2 --residual 4 --report '" + path("summary-all.json") + "'");
  const nlohmann::json all = read_json("summary-all.json");
  EXPECT_NE(unmasked.output.find("error " + five_digits(all["error_masked"]) + ","),
            std::string::npos)
      << unmasked.output;
  EXPECT_EQ(unmasked.output.find("whole frame"), std::string::npos) << unmasked.output;
}

TEST_F(FieldInputCommands, TheInputEncodingIsDecidedOnceAndSaid) {
  // The scene's images as 8-bit PNGs, without light_intensities.txt: sRGB by default.
  fs::create_directories(path("png"));
  std::ofstream names(path("png/filenames.txt"));
  std::ifstream exr_names(path("scene/filenames.txt"));
  for (std::string name; std::getline(exr_names, name);) {
    const std::string png = fs::path(name).replace_extension(".png").string();
    Image image = read_image(path("scene") + "/" + name);
    for (float& v : image.pixels) v = std::min(v, 1.0f);
    write_image(path("png/" + png), image);
    names << png << '\n';
  }
  names.close();
  fs::copy_file(path("scene/light_directions.txt"), path("png/light_directions.txt"));

  const auto automatic = run_or_fail("relight '" + path("png") + "' --lights '" +
                                     path("lights.txt") + "' -o '" + path("png-auto.exr") + "'");
  const std::string said = "decoded as sRGB";
  const auto at = automatic.output.find(said);
  EXPECT_NE(at, std::string::npos) << automatic.output;
  EXPECT_EQ(automatic.output.find(said, at + 1), std::string::npos) << "said once";
  const auto linear = run_or_fail("relight '" + path("png") + "' --linear --lights '" +
                                  path("lights.txt") + "' -o '" + path("png-linear.exr") + "'");
  EXPECT_NE(linear.output.find("linear, as asked"), std::string::npos) << linear.output;
  // sRGB decoding darkens mid-tones: the linear reading is brighter.
  EXPECT_GT(energy_in_columns(read_image(path("png-linear.exr")), 0, width),
            1.2 * energy_in_columns(read_image(path("png-auto.exr")), 0, width));
  const auto quiet = run_or_fail("-q relight '" + path("png") + "' --lights '" +
                                 path("lights.txt") + "' -o '" + path("png-quiet.exr") + "'");
  EXPECT_EQ(quiet.output, "");
  const auto bad =
      testing::run_relume("relight '" + path("png") + "' --input-encoding gamma --lights '" +
                          path("lights.txt") + "' -o '" + path("bad.exr") + "'");
  EXPECT_EQ(bad.exit_code, 2) << "a malformed option value is a usage error";
  EXPECT_NE(bad.output.find("gamma"), std::string::npos) << bad.output;
}

TEST_F(FieldInputCommands, CompareWithAMaskComparesInsideOnly) {
  Image reference(width, height, 3), image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        reference.at(x, y, c) = 1;
        image.at(x, y, c) = x < width / 2 ? 1.1f : 5.0f;  // far off outside the left half
      }
  write_image(path("reference.exr"), reference);
  write_image(path("image.exr"), image);
  run_or_fail("compare '" + path("image.exr") + "' '" + path("reference.exr") + "' --mask '" +
              path("left.png") + "' --json '" + path("compare.json") + "'");
  const nlohmann::json report = read_json("compare.json");
  EXPECT_NEAR(report["relative_squared_error"].get<double>(), 0.01, 1e-6);
  EXPECT_NEAR(report["max_abs_difference"].get<double>(), 0.1, 1e-6);
  EXPECT_EQ(report["values"], width / 2 * height * 3);
}

// An image given as the field was read as an .lp file ("expected the light count ..., found
// '\x89PNG'"): it is named as an image, with the folder to give instead.
TEST_F(FieldInputCommands, AnImageGivenAsTheFieldIsNamedAsOneWithTheFolderToGive) {
  std::ifstream names(path("scene/filenames.txt"));
  std::string first;
  std::getline(names, first);
  const std::string image = path("scene/" + first);
  for (const std::string& command :
       {"compress '" + image + "' -o '" + path("image-as-field.relume") + "'",
        "relight '" + image + "' --lights '" + path("lights.txt") + "' -o '" +
            path("image-as-field.exr") + "'"}) {
    const auto result = testing::run_relume(command);
    EXPECT_EQ(result.exit_code, 1) << command << "\n" << result.output;
    EXPECT_NE(result.output.find(image + " is an image, not a reflectance field: give the folder "
                                         "of the light images (DiLiGenT's layout, with "
                                         "light_directions.txt: " +
                                 path("scene") + " if that is it) or an RTI .lp file"),
              std::string::npos)
        << result.output;
    EXPECT_EQ(result.output.find("light count"), std::string::npos) << result.output;
  }
  EXPECT_FALSE(fs::exists(path("image-as-field.relume")));
  EXPECT_FALSE(fs::exists(path("image-as-field.exr")));
}

}  // namespace
}  // namespace relume
