// Test of scripts/device_bench.sh, the one-call GPU measurement of issue 16, in its --quick mode
// on PoCL with the built `relume`: it writes the files the device tool brings back, every record
// of both shapes (ceilings, GEMV, SpMV, single-frame relight, batched relight at B = 1, 4, 16 and
// 64, the assignment against the CPU path) with positive GB/s, the larger shape moves about 4x
// the bytes, and the summary quotes the device, its driver and both targets; a binary that does
// not start and a machine without a GPU (for the full run) are reported as such.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::run_command;

constexpr const char* pocl = "Portable Computing Language";

// The PoCL records of one report by kernel, batched ones by their batch size.
struct DeviceRecords {
  std::map<std::string, nlohmann::json> kernels;
  std::map<int, nlohmann::json> batched;
};

DeviceRecords pocl_records(const nlohmann::json& report) {
  DeviceRecords found;
  for (const auto& record : report["records"]) {
    if (record["platform"] != pocl) continue;
    EXPECT_GT(record["gbps"].get<double>(), 0) << record.dump();
    if (record["kernel"] == "relight_batched")
      EXPECT_TRUE(found.batched.emplace(record["frames"].get<int>(), record).second)
          << "one record per batch size: " << record.dump();
    else
      EXPECT_TRUE(found.kernels.emplace(record["kernel"].get<std::string>(), record).second)
          << "one record per kernel: " << record.dump();
  }
  return found;
}

TEST(DeviceBenchScript, QuickModeWritesEveryRecordAndASummary) {
  testing::TempDir out;
  const auto result = run_command("OUT='" + out.path().string() + "' RELUME_DEVICE=portable '" +
                                  (testing::source_dir() / "scripts" / "device_bench.sh").string() +
                                  "' --quick '" + RELUME_BINARY + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;

  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(out.path()))
    files.insert(entry.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"default.json", "large.json", "bench.log",
                                          "environment.txt", "summary.txt"}));

  const auto standard = nlohmann::json::parse(read_file(out / "default.json"));
  const auto large = nlohmann::json::parse(read_file(out / "large.json"));
  EXPECT_EQ(standard["field"]["width"], 32);
  EXPECT_EQ(large["field"]["width"], 64);
  EXPECT_EQ(standard["batch_frames"], nlohmann::json({1, 4, 16, 64}));
  ASSERT_EQ(standard["devices"].size(), 1u);
  EXPECT_EQ(standard["devices"][0]["platform"], pocl);
  EXPECT_FALSE(standard["devices"][0]["driver_version"].get<std::string>().empty());

  const DeviceRecords small_records = pocl_records(standard);
  const DeviceRecords large_records = pocl_records(large);
  for (const DeviceRecords* records : {&small_records, &large_records}) {
    for (const char* kernel : {"read", "copy", "gemv", "spmv", "relight"})
      EXPECT_TRUE(records->kernels.count(kernel)) << kernel;
    for (const int frames : {1, 4, 16, 64}) {
      ASSERT_TRUE(records->batched.count(frames)) << "B=" << frames;
      EXPECT_GT(records->batched.at(frames)["frames_per_second"].get<double>(), 0);
    }
  }
  // 4x the rows; only the light vectors and the products stay the same size.
  const double bytes_ratio = large_records.kernels.at("relight")["bytes"].get<double>() /
                             small_records.kernels.at("relight")["bytes"].get<double>();
  EXPECT_GT(bytes_ratio, 3.5);
  EXPECT_LT(bytes_ratio, 4.0);
  EXPECT_TRUE(small_records.kernels.count("assign"));
  EXPECT_FALSE(large_records.kernels.count("assign"));
  bool cpu_assign = false;
  for (const auto& record : standard["records"])
    cpu_assign |= record["platform"] == "reference" && record["kernel"] == "assign";
  EXPECT_TRUE(cpu_assign) << "the assignment's CPU path is benched for comparison";

  const std::string summary = read_file(out / "summary.txt");
  EXPECT_NE(summary.find("driver " + standard["devices"][0]["driver_version"].get<std::string>()),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("batched B=64"), std::string::npos) << summary;
  EXPECT_NE(summary.find("CPU path"), std::string::npos) << summary;
  std::size_t targets = 0;
  for (auto at = summary.find("targets: single-frame relight"); at != std::string::npos;
       at = summary.find("targets: single-frame relight", at + 1))
    ++targets;
  EXPECT_EQ(targets, 2u) << summary;
  EXPECT_NE(read_file(out / "environment.txt").find("relume devices:"), std::string::npos);
}

TEST(DeviceBenchScript, SaysWhenTheBinaryDoesNotStart) {
  testing::TempDir out;
  const auto missing = out / "no-relume-here";
  const auto result = run_command("OUT='" + out.path().string() + "' '" +
                                  (testing::source_dir() / "scripts" / "device_bench.sh").string() +
                                  "' --quick '" + missing.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find(missing.string() + " does not start"), std::string::npos)
      << result.output;
  EXPECT_NE(read_file(out / "environment.txt").find("glibc"), std::string::npos);
}

TEST(DeviceBenchScript, StopsWithoutAGpu) {
  if (testing::run_relume("devices").output.find(" gpu ") != std::string::npos)
    GTEST_SKIP() << "this machine has an OpenCL GPU: the full run would bench it";
  testing::TempDir out;
  const auto result = run_command("env -u RELUME_DEVICE OUT='" + out.path().string() + "' '" +
                                  (testing::source_dir() / "scripts" / "device_bench.sh").string() +
                                  "' '" + RELUME_BINARY + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("no OpenCL GPU"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(out / "default.json"));
}

}  // namespace
}  // namespace relume
