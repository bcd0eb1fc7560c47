// Tests of `relume compress` (run as a command on fields written to disk) and of the checkpoints
// it resumes from: containers and reports are written, a failing input does not stop the others,
// clusters beyond what the functions fill are warned of and their merging said, and a resumed
// clustering continues where the checkpoint left it.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <relume/error.hpp>
#include <relume/field.hpp>
#include <set>
#include <utility>
#include <vector>

#include "compress/checkpoint.hpp"
#include "compress/clustered_factorization.hpp"
#include "container/container.hpp"
#include "model/reconstruct_field.hpp"
#include "opencl/runtime.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

// Two planted clusters (2 terms, 24 lights) with one residual entry per function; the left half
// of the image is inside the mask. The functions are exact and spatially unrelated, so that no
// estimate tells them from noise: the tests give --noise-floor 0 (every function stored).
ReflectanceField small_field(std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> uniform(0.1f, 1.0f);
  ReflectanceField field;
  field.width = 16;
  field.height = 12;
  field.channels = 3;
  const int lights = 24;
  field.mask.assign(field.pixels(), 0);
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width / 2; ++x) field.mask[y * field.width + x] = 1;
  field.directions.resize(lights, 3);
  for (int i = 0; i < lights; ++i) {
    const float angle = 6.2831853f * i / lights;
    field.directions.row(i) << 0.6f * std::cos(angle), 0.6f * std::sin(angle), 0.8f;
  }
  field.intensities.setOnes(lights, 3);
  RowMatrixF bases[2] = {RowMatrixF(2, lights), RowMatrixF(2, lights)};
  for (auto& basis : bases)
    for (int i = 0; i < basis.size(); ++i) basis.data()[i] = uniform(random);
  field.values.resize(field.pixels() * field.channels, lights);
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    Eigen::RowVector2f w(uniform(random), uniform(random));
    field.values.row(p) = w * bases[(p / 3) % 2];
    field.values(p, static_cast<int>(random() % lights)) += uniform(random);
  }
  for (int i = 0; i < lights; ++i) field.image_names.push_back(std::to_string(i + 1) + ".exr");
  return field;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(CompressCommand, WritesAContainerAndAReport) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(1));
  const auto result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "out.relume").string() +
                          "' --clusters 2 --terms 2 --residual 1 --threads 2 --report '" +
                          (dir / "report.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const CompressedField compressed = read_container(dir / "out.relume");
  EXPECT_EQ(compressed.clusters, 2);
  EXPECT_EQ(compressed.terms, 2);
  EXPECT_EQ(compressed.stored_rows(), 16u * 12 / 2 * 3);  // the masked half
  const nlohmann::json report = read_json(dir / "report.json");
  for (const char* key : {"seconds", "bytes", "ratio", "error_all", "error_masked", "sections",
                          "sparseness", "peak_memory_bytes", "clustering", "phases_seconds"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["bytes"].get<std::uint64_t>(), std::filesystem::file_size(dir / "out.relume"));
  EXPECT_LT(report["error_masked"].get<double>(), 1e-4);
  // Outside the mask nothing is stored: those functions count as fully lost in error_all.
  EXPECT_GT(report["error_all"].get<double>(), 0.4);
  EXPECT_FALSE(report["clustering"]["iterations"].empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "out.relume.checkpoint"));
  // Stored quantized by default, within the 1% budget of Eq. 16 error (here every stored row is
  // in the budget's sample, so the bound holds for the whole field).
  const nlohmann::json& cost = report["precision_cost"];
  EXPECT_EQ(cost["weights"], "quantized");
  EXPECT_EQ(cost["residual_values"], "quantized");
  EXPECT_GE(cost["basis_bits"].get<int>(), 8);
  EXPECT_EQ(compressed.quantization.weight_step, cost["quantization"]["weight_step"].get<float>());
  EXPECT_LE(report["error_masked"].get<double>(),
            cost["error_masked_float32"].get<double>() * (1 + 0.01) + 1e-12);

  const auto exact = testing::run_relume(
      "compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
      (dir / "float.relume").string() +
      "' --clusters 2 --terms 2 --residual 1 --threads 2 --weights-precision float32 "
      "--residual-precision float32 --bases-precision float32 --report '" +
      (dir / "float.json").string() + "'");
  ASSERT_EQ(exact.exit_code, 0) << exact.output;
  EXPECT_FALSE(read_json(dir / "float.json").contains("precision_cost")) << "float32 costs nothing";
  EXPECT_FALSE(read_container(dir / "float.relume").quantization.any());
}

// More clusters than the functions fill were seeded without a word and merged without one
// (--clusters 2048 ended with 243): the run says so before seeding, and the summary says how many
// clusters remain of those asked and why.
TEST(CompressCommand, ClustersTheFunctionsCannotFillAreWarnedOfAndTheirMergingSaid) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(1));
  const auto result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "out.relume").string() +
                          "' --clusters 100 --terms 2 --residual 1 --threads 2 --report '" +
                          (dir / "report.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("100 clusters are more than 288 functions can fill (clusters with "
                               "fewer than 8 functions are merged into others): at most 36 will "
                               "remain"),
            std::string::npos)
      << result.output;
  const nlohmann::json report = read_json(dir / "report.json");
  const int clusters = report["parameters"]["clusters"].get<int>();
  int merged = 0;
  for (const auto& iteration : report["clustering"]["iterations"])
    merged += iteration["merged"].get<int>();
  EXPECT_LE(clusters, 36);
  EXPECT_GT(merged, 0);
  EXPECT_NE(result.output.find(", " + std::to_string(clusters) + " clusters of the 100 asked (" +
                               std::to_string(merged) +
                               " merged into others for having fewer than 8 functions), "),
            std::string::npos)
      << result.output;
}

// Without residual the planted spike of every function stays as a per-light error: the report
// says the largest one relative to its function's peak, and the negative values, as a direct
// reading of the stored file against the field on disk finds them.
TEST(CompressCommand, ReportsTheLargestPerLightErrorAndTheNegativeValues) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(3));
  const auto result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "out.relume").string() +
                          "' --clusters 2 --terms 2 --residual 0 --threads 2 --report '" +
                          (dir / "report.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const ReflectanceField original = load_field(dir / "field");
  const ReflectanceField rebuilt = reconstruct_field(read_container(dir / "out.relume"));
  double largest = 0;
  std::int64_t negative = 0, largest_function = -1;
  int largest_light = -1;
  for (std::int64_t p = 0; p < original.functions(); ++p) {
    if (!original.mask[p / 3]) continue;
    const double peak = original.values.row(p).cwiseAbs().maxCoeff();
    for (int i = 0; i < original.lights(); ++i) {
      const double error = std::abs(original.values(p, i) - rebuilt.values(p, i)) / peak;
      if (error > largest) {
        largest = error;
        largest_function = p;
        largest_light = i;
      }
      negative += original.values(p, i) >= 0 && rebuilt.values(p, i) < 0;
    }
  }
  const nlohmann::json report = read_json(dir / "report.json");
  const nlohmann::json& reported = report["per_light_error_masked"];
  EXPECT_GT(largest, 0.05);  // the spikes are at least 0.1 on peaks of at most ~2
  EXPECT_NEAR(reported["largest_relative"].get<double>(), largest, 1e-6);
  EXPECT_EQ(reported["largest_at"]["x"], (largest_function / 3) % 16);
  EXPECT_EQ(reported["largest_at"]["y"], (largest_function / 3) / 16);
  EXPECT_EQ(reported["largest_at"]["light"], largest_light);
  EXPECT_EQ(reported["negative_values"].get<std::int64_t>(), negative);
  EXPECT_EQ(reported["functions_measured"], 16 * 12 / 2 * 3);
  EXPECT_EQ(reported["values_measured"], 16 * 12 / 2 * 3 * 24);
  char expected[64];
  std::snprintf(expected, sizeof expected, "largest per-light error %.3g of its", largest);
  EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
}

TEST(CompressCommand, HalfPrecisionErrorIsMeasuredOnTheStoredFileAndItsCostReported) {
  testing::TempDir dir;
  const ReflectanceField field = small_field(2);
  write_field_folder(dir / "field", field);
  const auto result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "half.relume").string() +
                          "' --clusters 2 --terms 2 --residual 1 --weights-precision float16 "
                          "--residual-precision float16 --report '" +
                          (dir / "report.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json report = read_json(dir / "report.json");
  const double stored_error = relative_error(field, read_container(dir / "half.relume"), true).mean;
  EXPECT_NEAR(report["error_masked"].get<double>(), stored_error, 1e-12);
  const nlohmann::json& cost = report["precision_cost"];
  EXPECT_EQ(cost["weights"], "float16");
  EXPECT_EQ(cost["residual_values"], "float16");
  EXPECT_EQ(cost["error_masked_stored"].get<double>(), report["error_masked"].get<double>());
  // Half precision keeps about 3 decimal digits: its rounding moves the stored field's error by
  // a little (either way: the rounding is not aligned with the fit's own error), and the stored
  // field differs from the float32 one by quantization_error.
  EXPECT_NE(cost["error_masked_float32"].get<double>(), stored_error);
  EXPECT_NEAR(cost["error_masked_float32"].get<double>(), stored_error, 0.01 * stored_error);
  EXPECT_GT(cost["quantization_error"].get<double>(), 1e-9);
  EXPECT_LT(cost["quantization_error"].get<double>(), 1e-5);
}

TEST(CompressCommand, SeveralInputsGoToAFolderAndAFailureDoesNotStopTheOthers) {
  testing::TempDir dir;
  write_field_folder(dir / "first", small_field(2));
  write_field_folder(dir / "second", small_field(3));
  const auto result = testing::run_relume(
      "compress --noise-floor 0 '" + (dir / "first").string() + "' '" + (dir / "missing").string() +
      "' '" + (dir / "second").string() + "' -o '" + (dir / "out").string() +
      "' --clusters 2 --terms 2 --residual 10% --threads 2 --report '" +
      (dir / "report.json").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("missing"), std::string::npos) << result.output;
  EXPECT_NO_THROW(read_container(dir / "out" / "first.relume"));
  EXPECT_NO_THROW(read_container(dir / "out" / "second.relume"));
  const nlohmann::json report = read_json(dir / "report.json");
  EXPECT_EQ(report["runs"].size(), 2u);
  ASSERT_EQ(report["failed"].size(), 1u);
  EXPECT_NE(report["failed"][0]["input"].get<std::string>().find("missing"), std::string::npos);
}

TEST(CompressCommand, RefusesBadArguments) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(4));
  const std::string base = "compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                           (dir / "out.relume").string() + "' ";
  for (const char* bad : {"--residual 5%%", "--residual -2", "--terms 0", "--transform dct",
                          "--solver simplex", "--assign fpga", "--terms 30"}) {
    const auto result = testing::run_relume(base + bad);
    EXPECT_NE(result.exit_code, 0) << bad;
    EXPECT_NE(result.output.find("error"), std::string::npos) << bad << ": " << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out.relume"));
}

// --target-error: the error reached is at most the target, the container is the smallest of the
// (terms, clusters) pairs tried, and each function keeps a prefix of its sorted residual.
TEST(CompressCommand, TargetErrorReachesTheTargetWithTheSmallestContainerTried) {
  testing::TempDir dir;
  ReflectanceField field = small_field(3);
  std::mt19937_64 random(4);
  std::normal_distribution<float> noise(0.0f, 0.05f);
  for (std::int64_t i = 0; i < field.values.size(); ++i) field.values.data()[i] += noise(random);
  write_field_folder(dir / "field", field);
  const double target = 0.002;
  const auto result = testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() +
                                          "' -o '" + (dir / "t.relume").string() +
                                          "' --target-error " + std::to_string(target) +
                                          " --report '" + (dir / "report.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json report = read_json(dir / "report.json");
  const CompressedField compressed = read_container(dir / "t.relume");
  const double reached = relative_error(field, compressed, true).mean;
  EXPECT_LE(reached, target * (1 + 1e-6));
  EXPECT_NEAR(report["error_masked"].get<double>(), reached, 1e-12);

  const nlohmann::json& choice = report["target_error"];
  ASSERT_FALSE(choice["tried"].empty());
  std::uint64_t smallest = std::numeric_limits<std::uint64_t>::max();
  for (const auto& tried : choice["tried"]) {
    smallest = std::min(smallest, tried["bytes"].get<std::uint64_t>());
    EXPECT_LE(tried["error_over_stored_rows"].get<double>(), target * (1 + 1e-6));
  }
  EXPECT_EQ(choice["chosen"]["bytes"].get<std::uint64_t>(), smallest);
  EXPECT_EQ(choice["chosen"]["terms"].get<int>(), compressed.terms);
  // Per-function residual lengths differ, and the error needs some residual at this target.
  std::set<std::uint32_t> lengths;
  for (std::size_t r = 0; r < compressed.stored_rows(); ++r)
    lengths.insert(compressed.residual.row_offsets[r + 1] - compressed.residual.row_offsets[r]);
  EXPECT_GT(lengths.size(), 1u);
  EXPECT_GT(relative_error(field, compressed, true, 0).mean, target);
}

// --target-bytes over the clustered model: the file fits, the chosen way has the highest PSNR
// (over the frame) of the ways that fit, and a smaller budget keeps fewer residual entries at a
// lower PSNR. (The one-basis model's targets: tests/compress/one_basis_rate_test.cpp.)
TEST(CompressCommand, TargetBytesFitsWithTheHighestPsnrOfTheWaysTried) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(5));
  const auto compress = [&](const std::string& name, const std::string& target) {
    const auto result = testing::run_relume(
        "compress --noise-floor 0 --target-models clustered '" + (dir / "field").string() +
        "' -o '" +
                            (dir / (name + ".relume")).string() + "' " + target + " --report '" +
                            (dir / (name + ".json")).string() + "'");
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return read_json(dir / (name + ".json"));
  };
  const nlohmann::json roomy = compress("roomy", "--target-bytes 100000000");
  ASSERT_TRUE(roomy["rate_target"]["met"].get<bool>());
  std::uint64_t smallest = std::numeric_limits<std::uint64_t>::max();
  for (const auto& tried : roomy["rate_target"]["tried"])
    for (const auto& point : tried["points"])
      smallest = std::min(smallest, point["bytes"].get<std::uint64_t>());
  const std::uint64_t budget = (smallest + roomy["bytes"].get<std::uint64_t>()) / 2;

  const nlohmann::json tight = compress("tight", "--target-bytes " + std::to_string(budget));
  const nlohmann::json& choice = tight["rate_target"];
  EXPECT_TRUE(choice["met"].get<bool>());
  EXPECT_LE(std::filesystem::file_size(dir / "tight.relume"), budget);
  const auto frame_psnr = [](const nlohmann::json& report) {
    return report["psnr_8bit"]["whole_frame"].get<double>();
  };
  EXPECT_LT(frame_psnr(tight), frame_psnr(roomy));
  EXPECT_LT(tight["residual_nonzeros"].get<std::uint64_t>(),
            roomy["residual_nonzeros"].get<std::uint64_t>());
  const CompressedField stored = read_container(dir / "tight.relume");
  const nlohmann::json& chosen = choice["chosen"]["point"];
  EXPECT_NEAR(relative_error(small_field(5), stored, true).mean,
              chosen["error_masked"].get<double>(), 1e-9);
  const double chosen_psnr = chosen["psnr_8bit"].get<double>();
  EXPECT_NEAR(frame_psnr(tight), chosen_psnr, 1e-9);
  for (const auto& tried : choice["tried"])
    if (tried["met"].get<bool>()) {
      EXPECT_LE(tried["choice"]["bytes"].get<std::uint64_t>(), budget);
      EXPECT_LE(tried["choice"]["psnr_8bit"].get<double>(), chosen_psnr);
    }
  // Without --term-budget and --quantization-budget every pair is stored with term budgets 0 and
  // 0.1, each with quantization budgets 0.01, 0.1 and 1; with them, only so.
  std::set<std::pair<double, double>> ways;
  for (const auto& tried : choice["tried"])
    ways.insert({tried["term_budget"].get<double>(), tried["quantization_budget"].get<double>()});
  EXPECT_EQ(ways, (std::set<std::pair<double, double>>{
                      {0.0, 0.01}, {0.0, 0.1}, {0.0, 1.0}, {0.1, 0.01}, {0.1, 0.1}, {0.1, 1.0}}));
  const nlohmann::json given =
      compress("given", "--target-bytes " + std::to_string(budget) +
                            " --term-budget 0.05 --quantization-budget 0.2");
  for (const auto& tried : given["rate_target"]["tried"]) {
    EXPECT_EQ(tried["term_budget"].get<double>(), 0.05);
    EXPECT_EQ(tried["quantization_budget"].get<double>(), 0.2);
  }
}

// A byte target below the smallest container of the smallest (terms, clusters) pair: the larger
// pairs, which only add bytes, are not factored, and the explanation lists them.
TEST(CompressCommand, GridPairsThatCannotFitAreNotFactored) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(7));
  const auto result = testing::run_relume(
      "compress --noise-floor 0 --target-models clustered '" + (dir / "field").string() +
      "' -o '" + (dir / "t.relume").string() + "' --target-bytes 600 --report '" +
      (dir / "t.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("8 larger (terms, clusters) pairs not factored"), std::string::npos)
      << result.output;
  const nlohmann::json choice = read_json(dir / "t.json")["rate_target"];
  EXPECT_FALSE(choice["met"].get<bool>());
  std::set<std::pair<int, int>> factored, skipped;
  std::vector<nlohmann::json> stored, finer;
  for (const auto& tried : choice["tried"]) {
    factored.insert({tried["terms"].get<int>(), tried["clusters"].get<int>()});
    (tried.contains("points") ? stored : finer).push_back(tried);
  }
  // Of the pair's ways, only the coarsest is stored: its smallest container is already too large.
  ASSERT_EQ(stored.size(), 1u) << choice.dump();
  EXPECT_GT(stored[0]["points"][0]["bytes"].get<std::uint64_t>(), 600u) << "its smallest container";
  EXPECT_FALSE(finer.empty()) << choice.dump();
  for (const auto& way : finer) {
    EXPECT_LE(way["term_budget"].get<double>(), stored[0]["term_budget"].get<double>());
    EXPECT_LE(way["quantization_budget"].get<double>(),
              stored[0]["quantization_budget"].get<double>());
    EXPECT_NE(way["not_stored"].get<std::string>().find("coarser way"), std::string::npos);
  }
  for (const auto& pair : choice["not_factored"])
    skipped.insert({pair["terms"].get<int>(), pair["clusters"].get<int>()});
  EXPECT_EQ(factored.size(), 1u);
  EXPECT_EQ(factored.begin()->first, 2);
  EXPECT_EQ(skipped.size(), 8u);
  EXPECT_FALSE(skipped.contains(*factored.begin()));
}

// --target-psnr: the PSNR of the file as written reaches the target with the fewest bytes of the
// pairs that reach it; a target no pair reaches is said to be missed, not claimed.
TEST(CompressCommand, TargetPsnrIsReachedWithTheFewestBytesAndAMissIsSaid) {
  testing::TempDir dir;
  write_field_folder(dir / "field", small_field(6));
  const double target = 38;
  auto result = testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() +
                                    "' -o '" + (dir / "p.relume").string() + "' --target-psnr " +
                                    std::to_string(target) + " --target-region mask --report '" +
                                    (dir / "p.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json report = read_json(dir / "p.json");
  const nlohmann::json& choice = report["rate_target"];
  ASSERT_TRUE(choice["met"].get<bool>()) << choice.dump();
  EXPECT_GE(report["psnr_8bit"]["mask"].get<double>(), target);
  const std::uint64_t bytes = std::filesystem::file_size(dir / "p.relume");
  EXPECT_EQ(choice["chosen"]["point"]["bytes"].get<std::uint64_t>(), bytes);
  // The parameters name the model the file holds (one basis: its weights are JPEG 2000 planes).
  const bool planes = report["sections"]["weight_planes"].get<std::uint64_t>() > 0;
  EXPECT_EQ(report["parameters"]["model"], planes ? "one_basis" : "clustered");
  EXPECT_EQ(report["parameters"]["clusters"].get<int>(), read_container(dir / "p.relume").clusters);
  for (const auto& tried : choice["tried"]) {
    if (tried["met"].get<bool>()) {
      EXPECT_GE(tried["choice"]["bytes"].get<std::uint64_t>(), bytes);
    }
  }

  // The default region is the whole frame: the unstored half of small_field counts as lost, so
  // the same target needs more than the mask's PSNR can give and is missed.
  result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "f.relume").string() + "' --target-psnr " +
                          std::to_string(target) + " --report '" + (dir / "f.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json frame = read_json(dir / "f.json");
  EXPECT_EQ(frame["rate_target"]["met"].get<bool>(),
            frame["psnr_8bit"]["whole_frame"].get<double>() >= target);
  EXPECT_LT(frame["psnr_8bit"]["whole_frame"].get<double>(), target);

  result = testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                               (dir / "q.relume").string() + "' --target-psnr 300 --report '" +
                               (dir / "q.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_FALSE(read_json(dir / "q.json")["rate_target"]["met"].get<bool>());

  result =
      testing::run_relume("compress --noise-floor 0 '" + (dir / "field").string() + "' -o '" +
                          (dir / "r.relume").string() + "' --target-psnr 40 --target-bytes 1000");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("--target-bytes and --target-psnr are two targets"),
            std::string::npos)
      << result.output;
}

// scripts/check_error.py's output for ORIGINAL against DECOMPRESSED, with the error it printed.
struct IndependentCheck {
  std::string output;
  double error_masked = -1;
};

IndependentCheck check_error(const std::filesystem::path& original,
                             const std::filesystem::path& decompressed) {
  const auto result = testing::run_command(
      "/usr/bin/python3 '" + (testing::source_dir() / "scripts/check_error.py").string() + "' '" +
      original.string() + "' '" + decompressed.string() + "'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  IndependentCheck check{result.output};
  const std::string label = "error_masked (Eq. 16): ";
  const std::size_t at = result.output.find(label);
  EXPECT_NE(at, std::string::npos) << result.output;
  if (at != std::string::npos)
    check.error_masked = std::stod(result.output.substr(at + label.size()));
  return check;
}

// `relume compress INPUT OPTIONS` into FOLDER/c.relume, then `relume decompress` into
// DECOMPRESSED; returns the compression report.
nlohmann::json compress_and_decompress(const std::filesystem::path& input,
                                       const std::string& options,
                                       const std::filesystem::path& folder,
                                       const std::filesystem::path& decompressed) {
  const std::string container = (folder / "c.relume").string();
  auto result = testing::run_relume("compress '" + input.string() + "' -o '" + container + "' " +
                                    options + " --report '" + (folder / "c.json").string() + "'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  result = testing::run_relume("decompress '" + container + "' -o '" + decompressed.string() + "'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return read_json(folder / "c.json");
}

// Skips the test where the system python lacks what check_error.py needs.
#define REQUIRE_CHECK_ERROR_PYTHON()                                                          \
  if (testing::run_command("/usr/bin/python3 -c 'import numpy, OpenImageIO'").exit_code != 0) \
  GTEST_SKIP() << "/usr/bin/python3 lacks numpy or OpenImageIO (python3-numpy, "              \
                  "python3-openimageio)"

// The compress report's error recomputed from the decompressed EXRs by
// scripts/check_error.py (NumPy and OpenImageIO's Python bindings, none of relume's code).
TEST(CompressCommand, ReportedErrorMatchesAnIndependentCheckOnRealData) {
  RELUME_REQUIRE_SHARED_DATA(data);
  REQUIRE_CHECK_ERROR_PYTHON();
  testing::TempDir dir;
  const std::string bear = (data / "olat/diligent-bear-crop8").string();
  const nlohmann::json report =
      compress_and_decompress(bear, "--clusters 16 --terms 3 --residual 4 --iterations 2",
                              dir.path(), dir / "decompressed");
  const IndependentCheck check = check_error(bear, dir / "decompressed");

  const double reported = report["error_masked"].get<double>();
  EXPECT_GT(reported, 1e-4) << "a lossy setting, so the comparison means something";
  EXPECT_NEAR(check.error_masked, reported, 1e-4 * reported) << check.output;
  const auto& detail = report["error_masked_detail"];
  const std::string functions =
      "functions inside the mask: " + std::to_string(detail["functions_averaged"].get<int>() +
                                                     detail["zero_energy_skipped"].get<int>());
  EXPECT_NE(check.output.find(functions), std::string::npos) << check.output;
}

// A field folder without filenames.txt, its images numbered 1.exr ... 24.exr: relume and
// check_error.py both take them in the order of their numbers, so their errors agree (in name
// order 10.exr would be the second light and the two would differ).
TEST(CompressCommand, NumberedImagesWithoutAListingAreCheckedInTheSameOrder) {
  REQUIRE_CHECK_ERROR_PYTHON();
  testing::TempDir dir;
  const std::filesystem::path field = dir / "field";
  write_field_folder(field, small_field(5));
  std::filesystem::remove(field / "filenames.txt");
  for (int i = 1; i <= 24; ++i) {
    char padded[16];
    std::snprintf(padded, sizeof padded, "%03d.exr", i);
    std::filesystem::rename(field / padded, field / (std::to_string(i) + ".exr"));
  }
  const double reported = compress_and_decompress(field, "--clusters 2 --terms 1 --residual 1",
                                                  dir.path(), dir / "decompressed")["error_masked"]
                              .get<double>();
  EXPECT_GT(reported, 1e-4) << "one term for two-term clusters: a lossy setting";
  EXPECT_NEAR(check_error(field, dir / "decompressed").error_masked, reported, 1e-4 * reported);
}

// The assignment runs as the OpenCL kernel unless --assign cpu asks for the C++ path; both make
// the same choices on real data, so the containers' errors agree closely.
TEST(CompressCommand, OpenClAssignmentIsTheDefaultAndAgreesWithTheCpuPath) {
  RELUME_REQUIRE_SHARED_DATA(data);
  testing::TempDir dir;
  const std::string bear = (data / "olat/diligent-bear-crop8").string();
  std::map<std::string, nlohmann::json> reports;
  for (const std::string assign : {"", "--assign cpu"}) {
    const auto result =
        testing::run_relume("-y compress '" + bear + "' -o '" + (dir / "b.relume").string() +
                            "' --clusters 16 --terms 3 --residual 4 --iterations 2 --threads 2 " +
                            assign + " --report '" + (dir / "b.json").string() + "'");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    reports[assign] = read_json(dir / "b.json");
  }
  const std::string device = reports[""]["assignment_device"].get<std::string>();
  EXPECT_NE(device, "cpu");
  EXPECT_EQ(device, select_opencl_device().label());
  EXPECT_EQ(reports["--assign cpu"]["assignment_device"], "cpu");
  const double opencl = reports[""]["error_masked"].get<double>();
  const double cpu = reports["--assign cpu"]["error_masked"].get<double>();
  EXPECT_GT(cpu, 1e-4) << "a lossy setting, so the comparison means something";
  EXPECT_NEAR(opencl, cpu, 0.01 * cpu);
}

TEST(CompressCheckpoint, ResumingContinuesTheIterationsOfTheCheckpoint) {
  testing::TempDir dir;
  const ReflectanceField field = small_field(5);
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  options.clustering.quiet = true;
  options.clustering.max_iterations = 3;
  options.clustering.settle_fraction = -1;  // run every iteration
  options.residual.entries = 1;
  options.noise_floor = 0;  // small_field is exact: no noise to estimate

  // An interrupted run: keep the checkpoint of the second iteration.
  CompressionStats stats;
  int calls = 0;
  const auto checkpoint = dir / "run.checkpoint";
  compress_field(field, options, stats, [&](const ClusterModel& model, const IterationRecord&) {
    if (++calls == 2)
      write_checkpoint(checkpoint, "fingerprint", model, stats.clustering.iterations);
  });
  ASSERT_EQ(stats.clustering.iterations.size(), 4u);  // the first assignment and 3 iterations

  const ClusteringResume resume = read_checkpoint(checkpoint, "fingerprint");
  EXPECT_EQ(resume.iterations.size(), 2u);
  CompressionStats resumed_stats;
  const CompressedField resumed = compress_field(field, options, resumed_stats, {}, &resume);
  ASSERT_EQ(resumed_stats.clustering.iterations.size(), 4u);
  EXPECT_EQ(resumed_stats.clustering.iterations.back().iteration, 3);
  EXPECT_LT(relative_error(field, resumed, true).mean, 1e-4);

  EXPECT_THROW(read_checkpoint(checkpoint, "another input"), Error);
  std::filesystem::resize_file(checkpoint, std::filesystem::file_size(checkpoint) - 4);
  EXPECT_THROW(read_checkpoint(checkpoint, "fingerprint"), Error);
}

}  // namespace
}  // namespace relume
