// Tests of `mpirun -n N relume compress` (the command built with MPI,
// apps/commands/compress/mpi_ranks.*): 1, 2 and 3 ranks on loopback compress one field (streamed)
// within 1% of one process's error, to the same container and, measured band by band, the same
// errors as one rank, a rank count gives the same bytes every time, the report says how the ranks
// shared the work (with the compressed field gathered in memory, and with it on disk, each rank's
// strips sent to the root), the root clusters the sample on the cores of the ranks bound beside it
// (which wait for it), and a failure on one rank (a truncated image under its rows only) ends every
// rank with that rank's message and leaves no output.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

// The MPI launcher CMake found (FindMPI's MPIEXEC_EXECUTABLE); empty when built without MPI.
#ifdef RELUME_MPIRUN
constexpr const char* mpirun = RELUME_MPIRUN;
#else
constexpr const char* mpirun = "";
#endif

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

class MpiCompress : public ::testing::Test {
 protected:
  void SetUp() override {
#ifndef RELUME_MPIRUN
    GTEST_SKIP() << "relume was built without MPI (RELUME_MPI off: libopenmpi-dev missing)";
#else
    const auto synth = testing::run_relume("-q synth -o '" + (dir_ / "scene").string() +
                                           "' --size 64x64 --lights 32 --samples 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    // Few lights and 8 residual entries a row: the compressed field outweighs the strips, and
    // under 3 MB it is built on disk.
    const auto few = testing::run_relume("-q synth -o '" + (dir_ / "few_lights").string() +
                                         "' --size 96x96 --lights 16 --samples 1");
    ASSERT_EQ(few.exit_code, 0) << few.output;
#endif
  }

  // `[mpirun -n ranks] relume compress dir/scene -o dir/name.relume --report dir/name.json
  // [extra]` (`launch`: more options of mpirun); ranks 0: without mpirun. The memory limit makes
  // one process stream too (the 64x64 field is 1.5 MB as float32, 3.8 MB to compress in memory), so
  // that all compare the same method.
  testing::CommandResult compress(int ranks, const std::string& name,
                                  const std::string& scene = "scene", const std::string& extra = "",
                                  const std::string& launch = "") {
    const std::string relume =
        ranks == 0 ? std::string(RELUME_BINARY)
                   : std::string(mpirun) + " --allow-run-as-root --oversubscribe " + launch +
                         " -n " + std::to_string(ranks) + " " + RELUME_BINARY;
    return testing::run_command(
        relume + " -q --memory-limit 3M compress '" + (dir_ / scene).string() + "' -o '" +
        (dir_ / (name + ".relume")).string() + "' --report '" + (dir_ / (name + ".json")).string() +
        "' --clusters 16 --threads 1 " + extra + " 2>&1");
  }

  // One process, then 1, 2 and 3 ranks, then 2 ranks again, on `scene`: the plan holds the
  // compressed field on disk or not.
  void expect_ranks_share_the_work(const std::string& scene, const std::string& extra,
                                   bool on_disk) {
    const auto single = compress(0, "single", scene, extra);
    ASSERT_EQ(single.exit_code, 0) << single.output;
    const double single_error = read_json(dir_ / "single.json")["error_masked"].get<double>();
    for (const int ranks : {1, 2, 3}) {
      const std::string name = "ranks" + std::to_string(ranks);
      const auto run = compress(ranks, name, scene, extra);
      ASSERT_EQ(run.exit_code, 0) << run.output;
      const nlohmann::json report = read_json(dir_ / (name + ".json"));
      EXPECT_EQ(report["plan"]["ranks"].get<int>(), ranks);
      EXPECT_EQ(report["plan"]["compressed_on_disk"].get<bool>(), on_disk);
      if (ranks > 1) {
        EXPECT_TRUE(report["plan"]["streamed"].get<bool>()) << "several ranks always stream";
        EXPECT_EQ(report["streamed"]["rank_bytes_sent"].size(), std::size_t(ranks));
        EXPECT_EQ(report["streamed"]["rank_compute_seconds"].size(), std::size_t(ranks));
        EXPECT_EQ(report["streamed"]["rank_build_seconds"].size(), std::size_t(ranks));
        EXPECT_GT(report["streamed"]["rank_bytes_sent"][1].get<double>(), 0);
        // The bands hold the same stored functions to within two pixel rows', all of them together
        // one rank's.
        const auto shares =
            report["streamed"]["rank_stored_functions"].get<std::vector<std::uint64_t>>();
        ASSERT_EQ(shares.size(), std::size_t(ranks));
        const auto [fewest, most] = std::minmax_element(shares.begin(), shares.end());
        EXPECT_LE(*most - *fewest, 2u * report["field"]["width"].get<std::uint64_t>() * 3u);
        EXPECT_EQ(std::accumulate(shares.begin(), shares.end(), std::uint64_t(0)),
                  read_json(dir_ / "ranks1.json")["streamed"]["rank_stored_functions"][0]
                      .get<std::uint64_t>());
      }
      if (ranks > 1) {
        // The same model as one rank's, whose errors each rank measured on its own band of rows:
        // merged at the root they are one rank's (up to the order of the sums), down to where the
        // largest per-light error is.
        const nlohmann::json one = read_json(dir_ / "ranks1.json");
        EXPECT_TRUE(read_file(dir_ / (name + ".relume")) == read_file(dir_ / "ranks1.relume"));
        EXPECT_NEAR(report["psnr_8bit"]["whole_frame"].get<double>(),
                    one["psnr_8bit"]["whole_frame"].get<double>(), 1e-9);
        EXPECT_NEAR(report["psnr_8bit"]["mask"].get<double>(),
                    one["psnr_8bit"]["mask"].get<double>(), 1e-9);
        EXPECT_NEAR(report["error_all"].get<double>(), one["error_all"].get<double>(), 1e-12);
        const nlohmann::json& light = report["per_light_error_masked"];
        const nlohmann::json& one_light = one["per_light_error_masked"];
        EXPECT_EQ(light["largest_at"], one_light["largest_at"]);
        EXPECT_EQ(light["largest_relative"], one_light["largest_relative"]);
        EXPECT_EQ(light["functions_measured"], one_light["functions_measured"]);
        EXPECT_EQ(light["negative_values"], one_light["negative_values"]);
        EXPECT_EQ(report["error_masked_detail"]["functions_averaged"],
                  one["error_masked_detail"]["functions_averaged"]);
        // Every pass, the build pass too (whose bands are not the refinement's: each rank gets
        // its rows' clusters of the last pass moved to it), changed the clusters of as many rows.
        const nlohmann::json &passes = report["streamed"]["passes"],
                             &one_passes = one["streamed"]["passes"];
        ASSERT_EQ(passes.size(), one_passes.size());
        for (std::size_t p = 0; p < passes.size(); ++p)
          EXPECT_EQ(passes[p]["changed"], one_passes[p]["changed"]) << "pass " << p + 1;
      }
      const double error = report["error_masked"].get<double>();
      std::printf("%d ranks: error_masked %.6f (one process, no mpirun: %.6f)\n", ranks, error,
                  single_error);
      EXPECT_NEAR(error, single_error, 0.01 * single_error);
      for (const auto& entry : fs::directory_iterator(dir_.path()))
        EXPECT_FALSE(entry.path().filename().string().starts_with(".tmp-"))
            << "a scratch file is left: " << entry.path();
    }
    const auto again = compress(2, "again", scene, extra);
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_TRUE(read_file(dir_ / "again.relume") == read_file(dir_ / "ranks2.relume"))
        << "two ranks give the same container every time";
  }

  testing::TempDir dir_;
};

TEST_F(MpiCompress, RanksShareTheWorkAndReachTheSingleProcessQuality) {
  expect_ranks_share_the_work("scene", "", false);
}

TEST_F(MpiCompress, RanksBuildTheCompressedFieldOnDiskAndTheRootGathersIt) {
  expect_ranks_share_the_work("few_lights", "--residual 8", true);
}

TEST_F(MpiCompress, TheRootClustersTheSampleOnTheCoresOfTheRanksBesideIt) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs two cores to bind two ranks";
  // Each rank bound to one core, one thread each: the root's sample clustering runs on both.
  const auto two = compress(2, "bound2", "scene", "", "--bind-to core");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  const nlohmann::json streamed = read_json(dir_ / "bound2.json")["streamed"];
  EXPECT_EQ(streamed["sample_clustering_cores"].get<int>(), 2);
  EXPECT_EQ(streamed["sample_clustering_threads"].get<int>(), 2);
  const auto one = compress(1, "bound1", "scene", "", "--bind-to core");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const nlohmann::json alone = read_json(dir_ / "bound1.json")["streamed"];
  EXPECT_EQ(alone["sample_clustering_cores"].get<int>(), 1);
  EXPECT_EQ(alone["sample_clustering_threads"].get<int>(), 1);
  EXPECT_TRUE(read_file(dir_ / "bound2.relume") == read_file(dir_ / "bound1.relume"))
      << "the model does not depend on the threads that clustered the sample";
}

TEST_F(MpiCompress, AFailureOnOneRankEndsEveryRankWithItsMessage) {
  // The last light's image loses its bottom rows, which the first of three ranks never reads.
  const fs::path image = dir_ / "scene" / "032.exr";
  fs::resize_file(image, fs::file_size(image) * 6 / 10);
  const auto run = compress(3, "failed");
  EXPECT_NE(run.exit_code, 0) << run.output;
  // The rank whose rows reach the lost part says so (which one depends on the image's bytes).
  EXPECT_TRUE(run.output.find("relume (rank 1 of 3): error:") != std::string::npos ||
              run.output.find("relume (rank 2 of 3): error:") != std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("032.exr"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "failed.relume"));
  EXPECT_FALSE(fs::exists(dir_ / "failed.json"));
}

}  // namespace
}  // namespace relume
