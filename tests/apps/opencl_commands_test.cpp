// Tests of the `relume devices` and `relume bench` commands, run as the built binary on PoCL: the
// listing marks the default device, the benchmark writes one JSON record per (device, kernel)
// with the required fields (assignment included; batched relight once per --frames batch size)
// and names the devices it benched, the --container sweep writes one record per
// residual cap with errors that fall as the cap grows, and bad options fail with a message.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::run_relume;

TEST(DevicesCommand, ListsPoclAndMarksTheDefault) {
  const auto result = run_relume("devices");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("Portable Computing Language"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("\n* "), std::string::npos)
      << "a default marked *: " << result.output;
}

TEST(BenchCommand, WritesOneRecordPerDeviceAndKernel) {
  testing::TempDir folder;
  const auto json_path = folder / "bench.json";
  const auto result = run_relume(
      "bench --device portable --width 16 --height 8 --lights 9 --clusters 3 --terms 3 "
      "--residual 4 --cap 2 --repeats 3 --frames 3,5 --ceiling-mib 4 --assign-rows 64 --json '" +
      json_path.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("relight_batched"), std::string::npos) << result.output;
  const auto json = nlohmann::json::parse(read_file(json_path));
  EXPECT_EQ(json["field"]["stored_rows"], 16 * 8 * 3);
  EXPECT_EQ(json["batch_frames"], nlohmann::json({3, 5}));
  ASSERT_EQ(json["devices"].size(), 1u);
  EXPECT_EQ(json["devices"][0]["platform"], "Portable Computing Language");
  EXPECT_EQ(json["devices"][0]["type"], "cpu");
  EXPECT_FALSE(json["devices"][0]["driver_version"].get<std::string>().empty());
  std::set<std::pair<std::string, std::string>> seen;
  std::map<int, double> batched_bytes;  // PoCL's relight_batched records by batch size
  for (const auto& record : json["records"]) {
    for (const char* key :
         {"platform", "device", "kernel", "bytes", "seconds", "gbps", "ratio_to_peak"})
      ASSERT_TRUE(record.contains(key)) << key << " missing in " << record.dump();
    const std::string platform = record["platform"];
    const std::string kernel = record["kernel"];
    seen.insert({platform, kernel});
    EXPECT_GT(record["bytes"].get<double>(), 0) << record.dump();
    EXPECT_GT(record["seconds"].get<double>(), 0) << record.dump();
    EXPECT_NEAR(record["gbps"].get<double>(),
                1e-9 * record["bytes"].get<double>() / record["seconds"].get<double>(), 1e-6);
    if (platform != "reference") {
      EXPECT_NEAR(record["ratio_to_peak"].get<double>(),
                  record["gbps"].get<double>() / record["peak_gbps"].get<double>(), 1e-9);
    }
    if (kernel == "relight_batched") {
      EXPECT_TRUE(batched_bytes.emplace(record["frames"].get<int>(), record["bytes"]).second)
          << "one record per batch size: " << record.dump();
    }
    if (kernel == "spmv" || kernel == "relight") {
      EXPECT_EQ(record["residual_cap"], 2);
    }
    if (platform != "reference" && kernel != "read" && kernel != "copy" && kernel != "assign") {
      // 384 rows of 4 entries each: 128-row slices are the tallest without padding rows.
      EXPECT_EQ(record["layout"]["slice_rows"], 128) << record.dump();
      EXPECT_EQ(record["layout"]["work_group_rows"], 1024) << record.dump();
      EXPECT_EQ(record["layout"]["row_vector"], 16) << record.dump();
      EXPECT_EQ(record["layout"]["head_entries"], 24) << record.dump();
    }
    if (platform != "reference" && (kernel == "relight" || kernel == "relight_batched")) {
      // On a roofline of two roofs: 384 rows x (3 terms + 2 of the cap's entries) multiply-adds
      // per frame in the row kernel, besides the GEMV's and the dark pixels'.
      const int frames = record["frames"].get<int>();
      EXPECT_GE(record["flops"].get<double>(), 2.0 * frames * 384 * (3 + 2)) << record.dump();
      EXPECT_NEAR(record["arithmetic_intensity"].get<double>(),
                  record["flops"].get<double>() / record["bytes"].get<double>(), 1e-9);
      const double memory = record["memory_ceiling_seconds"].get<double>();
      const double work = record["work_ceiling_seconds"].get<double>();
      EXPECT_GT(work, 0) << record.dump();
      EXPECT_EQ(record["binding_ceiling"], memory >= work ? "memory" : "work") << record.dump();
      EXPECT_NEAR(record["ratio_to_binding_ceiling"].get<double>(),
                  std::max(memory, work) / record["seconds"].get<double>(), 1e-9);
    }
    if (kernel == "assign") {
      // 64 rows x 9 lights, 64 x 3 candidates, 3 clusters x 3 terms x 9 lights of bases read;
      // best, second, objective and 3 weights written per row; all 4 bytes each.
      EXPECT_EQ(record["bytes"], 4 * (64 * 9 + 64 * 3 + 3 * 3 * 9 + 64 * (3 + 3))) << record.dump();
      EXPECT_EQ(record["fits"], 64 * 3) << record.dump();
      EXPECT_NEAR(record["fits_per_second"].get<double>(), 64 * 3 / record["seconds"].get<double>(),
                  1e-6 * record["fits_per_second"].get<double>());
      EXPECT_GT(record["gbps"].get<double>(), 0) << record.dump();
      EXPECT_FALSE(record.contains("residual_cap")) << record.dump();
      if (platform != "reference")
        EXPECT_GE(record["wall_seconds"].get<double>(), record["seconds"].get<double>());
    }
  }
  for (const char* kernel :
       {"read", "copy", "gemv", "spmv", "relight", "relight_batched", "assign"})
    EXPECT_TRUE(seen.count({"Portable Computing Language", kernel})) << kernel;
  for (const char* kernel : {"gemv", "spmv", "relight", "assign"})
    EXPECT_TRUE(seen.count({"reference", kernel})) << kernel;
  // One record per --frames batch size; a larger batch writes more frames from the same reads.
  ASSERT_EQ(batched_bytes.size(), 2u);
  ASSERT_TRUE(batched_bytes.count(3) && batched_bytes.count(5));
  EXPECT_GT(batched_bytes[5], batched_bytes[3]);
  EXPECT_EQ(json["assignment"]["rows"], 64);
  EXPECT_EQ(json["assignment"]["candidates"], 3);
}

// A 32x32 synthetic field of 40 lights and its compression with 8 residual entries per function;
// returns the compression report.
nlohmann::json make_small_container(const testing::TempDir& folder) {
  const auto field = folder / "field";
  auto result =
      run_relume("synth -o '" + field.string() + "' --size 32x32 --lights 40 --samples 1");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  result =
      run_relume("compress '" + field.string() + "' -o '" + (folder / "small.relume").string() +
                 "' --clusters 4 --terms 2 --residual 8 --threads 2 -q --report '" +
                 (folder / "report.json").string() + "'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return nlohmann::json::parse(read_file(folder / "report.json"));
}

// The sweep's relight records of one platform, in the order written.
std::vector<nlohmann::json> sweep_records(const nlohmann::json& json, const std::string& platform,
                                          const std::string& kernel) {
  std::vector<nlohmann::json> records;
  for (const auto& record : json["records"])
    if (record["platform"] == platform && record["kernel"] == kernel) records.push_back(record);
  return records;
}

// Runs the sweep on PoCL and checks what every sweep does; returns the JSON.
nlohmann::json run_sweep(const testing::TempDir& folder, const std::string& extra) {
  const auto json_path = folder / "sweep.json";
  const auto result =
      run_relume("bench --device portable --container '" + (folder / "small.relume").string() +
                 "' --repeats 2 --frames 2 --ceiling-mib 4 --assign-rows 0 "
                 "--threads 2 --json '" +
                 json_path.string() + "' " + extra);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("residual sweep"), std::string::npos) << result.output;
  const auto json = nlohmann::json::parse(read_file(json_path));
  EXPECT_EQ(json["field"]["source"], "container");
  EXPECT_EQ(json["field"]["lights"], 40);
  // 0, 3, 5, 10, 20, 30% of 40 lights, rounded; then the full residual.
  const std::vector<nlohmann::json> caps = {0, 1, 2, 4, 8, 12, "all"};
  const std::vector<nlohmann::json> percents = {0, 3, 5, 10, 20, 30, "all"};
  for (const char* platform : {"Portable Computing Language", "reference"}) {
    for (const char* kernel : {"relight", "relight_batched"}) {
      if (std::string(platform) == "reference" && std::string(kernel) == "relight_batched")
        continue;
      const auto records = sweep_records(json, platform, kernel);
      EXPECT_EQ(records.size(), caps.size()) << platform << " " << kernel;
      for (std::size_t i = 0; i < records.size() && i < caps.size(); ++i) {
        const auto& record = records[i];
        EXPECT_EQ(record["residual_cap"], caps[i]) << record.dump();
        EXPECT_EQ(record["residual_percent"], percents[i]) << record.dump();
        EXPECT_GT(record["bytes"].get<double>(), 0) << record.dump();
        EXPECT_GT(record["seconds"].get<double>(), 0) << record.dump();
        EXPECT_GT(record["frames_per_second"].get<double>(), 0) << record.dump();
        if (i > 0) {
          EXPECT_LE(record["error"].get<double>(), records[i - 1]["error"].get<double>())
              << record.dump();
          // More entries read per row, up to the 8 stored.
          EXPECT_GE(record["bytes"].get<double>(), records[i - 1]["bytes"].get<double>());
        }
      }
      if (std::string(platform) != "reference" && !records.empty())
        EXPECT_GT(records.front()["wall_frames_per_second"].get<double>(), 0);
    }
  }
  // With --container there are no random-field or component records.
  for (const auto& record : json["records"])
    EXPECT_TRUE(record["kernel"] != "gemv" && record["kernel"] != "spmv") << record.dump();
  return json;
}

TEST(BenchCommand, SweepsTheResidualOfAContainer) {
  testing::TempDir folder;
  make_small_container(folder);
  const auto json = run_sweep(folder, "");
  EXPECT_EQ(json["sweep"]["error_against"], "container");
  const auto records = sweep_records(json, "Portable Computing Language", "relight");
  ASSERT_EQ(records.size(), 7u);
  EXPECT_GT(records[0]["error"].get<double>(), 0.01) << "no residual at all";
  // 8 entries are stored: caps 8, 12 and all relight the container itself.
  for (std::size_t i = 4; i < 7; ++i) EXPECT_LT(records[i]["error"].get<double>(), 1e-7);
  EXPECT_GT(records[3]["error"].get<double>(), 1e-6) << "cap 4 of 8 entries";
}

TEST(BenchCommand, SweepsAgainstTheOriginalField) {
  testing::TempDir folder;
  const auto report = make_small_container(folder);
  const auto json = run_sweep(folder, "--field '" + (folder / "field").string() + "'");
  EXPECT_EQ(json["sweep"]["error_against"], "field");
  const auto records = sweep_records(json, "Portable Computing Language", "relight");
  ASSERT_EQ(records.size(), 7u);
  // The full residual's error is the compressor's own masked error.
  const double masked = report["error_masked"].get<double>();
  EXPECT_GT(masked, 0);
  EXPECT_NEAR(records[6]["error"].get<double>(), masked, 1e-9 * masked);
  EXPECT_GT(records[0]["error"].get<double>(), records[6]["error"].get<double>());
}

TEST(BenchCommand, RefusesBadOptions) {
  auto result = run_relume("bench --frames 0 --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("--frames 0"), std::string::npos) << result.output;
  result = run_relume("bench --frames 4,40 --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("--frames 40 (expected 1 to --max-batch 32)"), std::string::npos)
      << result.output;
  result = run_relume("bench --device no-such-device-anywhere --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("no-such-device-anywhere"), std::string::npos) << result.output;
  result = run_relume("bench --width 0 --repeats 1 --device portable");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  result = run_relume("bench --assign-rows -1 --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("--assign-rows -1"), std::string::npos) << result.output;
}

TEST(BenchCommand, RefusesBadContainersAndFields) {
  testing::TempDir folder;
  const auto missing = folder / "missing.relume";
  auto result = run_relume("bench --repeats 1 --container '" + missing.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find(missing.string()), std::string::npos) << result.output;

  make_small_container(folder);
  const auto corrupt = folder / "corrupt.relume";
  const std::string bytes = read_file(folder / "small.relume");
  write_file_atomically(corrupt, bytes.substr(0, bytes.size() / 2));
  result = run_relume("bench --repeats 1 --container '" + corrupt.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find(corrupt.string()), std::string::npos) << result.output;

  const auto other = folder / "other";
  ASSERT_EQ(run_relume("synth -o '" + other.string() + "' --size 16x32 --lights 40 --samples 1")
                .exit_code,
            0);
  result = run_relume("bench --repeats 1 --container '" + (folder / "small.relume").string() +
                      "' --field '" + other.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("--field " + other.string()), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("16x32"), std::string::npos) << result.output;

  result = run_relume("bench --repeats 1 --field '" + other.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("needs --container"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace relume
