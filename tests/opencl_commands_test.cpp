// Tests of the `relume devices` and `relume bench` commands, run as the built binary on PoCL: the
// listing marks the default device, the benchmark writes one JSON record per (device, kernel)
// with the required fields, and bad options fail with a message.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "atomic_file.hpp"
#include "test_support.hpp"

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
      "--residual 4 --cap 2 --repeats 3 --frames 3 --ceiling-mib 4 --json '" +
      json_path.string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("relight_batched"), std::string::npos) << result.output;
  const auto json = nlohmann::json::parse(read_file(json_path));
  EXPECT_EQ(json["field"]["stored_rows"], 16 * 8 * 3);
  std::set<std::pair<std::string, std::string>> seen;
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
      EXPECT_EQ(record["frames"], 3);
    }
    if (kernel == "spmv" || kernel == "relight") {
      EXPECT_EQ(record["residual_cap"], 2);
    }
  }
  for (const char* kernel : {"read", "copy", "gemv", "spmv", "relight", "relight_batched"})
    EXPECT_TRUE(seen.count({"Portable Computing Language", kernel})) << kernel;
  for (const char* kernel : {"gemv", "spmv", "relight"})
    EXPECT_TRUE(seen.count({"reference", kernel})) << kernel;
}

TEST(BenchCommand, RefusesBadOptions) {
  auto result = run_relume("bench --frames 0 --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("--frames 0"), std::string::npos) << result.output;
  result = run_relume("bench --device no-such-device-anywhere --repeats 1");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("no-such-device-anywhere"), std::string::npos) << result.output;
  result = run_relume("bench --width 0 --repeats 1 --device portable");
  EXPECT_EQ(result.exit_code, 1) << result.output;
}

}  // namespace
}  // namespace relume
