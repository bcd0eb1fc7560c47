// Tests of `relume eval` and `relume compress --method cpca`, run as commands on a small synthetic
// scene: eval writes every CSV with its columns and plausible content, the per-pixel map, the
// relit images, the JSON summary and every plot (real PNGs drawn by matplotlib); compress writes a
// clustered PCA container that relights; bad settings are refused with the value named.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <relume/image.hpp>
#include <sstream>

#include "field/npy.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

struct Csv {
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;
};

Csv read_csv(const fs::path& path) {
  std::ifstream in(path);
  Csv csv;
  std::string line;
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream stream(text);
    std::string cell;
    while (std::getline(stream, cell, ',')) cells.push_back(cell);
    if (!text.empty() && text.back() == ',') cells.emplace_back();
    return cells;
  };
  if (!std::getline(in, line)) return csv;
  csv.columns = split(line);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < csv.columns.size() && c < cells.size(); ++c)
      row[csv.columns[c]] = cells[c];
    csv.rows.push_back(row);
  }
  return csv;
}

double value(const std::map<std::string, std::string>& row, const std::string& column) {
  return std::stod(row.at(column));
}

// A 40x32 synthetic scene (full sphere of 48 lights), made once for the suite.
class EvalCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new testing::TempDir;
    const auto synth = testing::run_relume("synth -q -o " + (scene()).string() +
                                           " --size 40x32 --lights 48 --samples 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }
  static void TearDownTestSuite() { delete scratch_; }
  static fs::path scene() { return scratch_->path() / "scene"; }
  static testing::TempDir* scratch_;
};

testing::TempDir* EvalCommand::scratch_ = nullptr;

TEST_F(EvalCommand, WritesEveryTableAndPlot) {
  testing::TempDir temp;
  const fs::path out = temp / "eval";
  const auto run = testing::run_relume(
      "eval " + scene().string() + " -o " + out.string() +
      " --clusters 4,8 --terms 2,3 --entries 0,1,3 --refit-entries 0,1 --compare-entries 1 "
      "--frames 2 --threads 2 --assign cpu");
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const Csv errors = read_csv(out / "error_vs_entries.csv");
  EXPECT_EQ(errors.columns,
            (std::vector<std::string>{"method", "clusters", "terms", "clusters_used", "refit_for",
                                      "entries", "error_all", "error_diffuse", "error_specular"}));
  // 4 configurations x (3 dynamic methods x 3 entries + 2 refits).
  EXPECT_EQ(errors.rows.size(), 4u * (3 * 3 + 2));
  std::map<std::string, double> at;  // method/clusters/terms/entries -> error_all
  for (const auto& row : errors.rows) {
    const double all = value(row, "error_all");
    EXPECT_GE(all, 0.0);
    EXPECT_LT(all, 1.0);
    at[row.at("method") + "/" + row.at("clusters") + "/" + row.at("terms") + "/" +
       row.at("entries")] = all;
  }
  // More residual entries never hurt a dynamic run; more terms help; the refit never loses at
  // its budget.
  for (const std::string method : {"l1", "cpca", "cpca-mean"}) {
    EXPECT_LE(at[method + "/8/3/3"], at[method + "/8/3/1"]);
    EXPECT_LE(at[method + "/8/3/1"], at[method + "/8/3/0"]);
    EXPECT_GT(at[method + "/8/3/0"], 0.0);
  }
  EXPECT_LT(at["l1/8/3/0"], at["l1/8/2/0"]);
  EXPECT_LE(at["l1-refit/8/3/0"], at["l1/8/3/0"] * (1 + 1e-6));
  EXPECT_LE(at["l1-refit/8/3/1"], at["l1/8/3/1"] * (1 + 1e-6));

  const Csv ratios = read_csv(out / "error_ratio.csv");
  EXPECT_EQ(ratios.columns,
            (std::vector<std::string>{"clusters", "terms", "entries", "method", "ratio_all",
                                      "ratio_diffuse", "ratio_specular"}));
  EXPECT_EQ(ratios.rows.size(), 4u * (3 + 2));
  for (const auto& row : ratios.rows) {
    const std::string key =
        "/" + row.at("clusters") + "/" + row.at("terms") + "/" + row.at("entries");
    EXPECT_NEAR(value(row, "ratio_all"), at["cpca" + key] / at[row.at("method") + key],
                1e-5 * value(row, "ratio_all"));
  }

  const Csv sparseness = read_csv(out / "sparseness.csv");
  EXPECT_EQ(sparseness.columns, (std::vector<std::string>{"method", "clusters", "terms",
                                                          "threshold", "fraction_at_or_below"}));
  EXPECT_EQ(sparseness.rows.size(), 4u * 3 * 25);
  double previous = -1;
  for (const auto& row : sparseness.rows) {
    if (row.at("method") != "l1" || row.at("clusters") != "8" || row.at("terms") != "3") continue;
    EXPECT_GE(value(row, "fraction_at_or_below"), previous);  // rises with the threshold
    previous = value(row, "fraction_at_or_below");
  }
  EXPECT_GT(previous, 0.9);

  const Csv rate = read_csv(out / "rate_distortion.csv");
  EXPECT_EQ(rate.columns, (std::vector<std::string>{"method", "clusters", "terms", "entries",
                                                    "bytes", "bytes_per_pixel", "ratio",
                                                    "error_masked", "psnr_mask", "psnr_frame"}));
  EXPECT_EQ(rate.rows.size(), 4u * (3 * 3 + 2));
  std::map<std::string, double> bytes;
  for (const auto& row : rate.rows) {
    EXPECT_GT(value(row, "bytes"), 100);
    EXPECT_NEAR(value(row, "bytes_per_pixel"), value(row, "bytes") / (40 * 32), 1e-6);
    EXPECT_GT(value(row, "psnr_mask"), 10);
    bytes[row.at("method") + "/" + row.at("clusters") + "/" + row.at("terms") + "/" +
          row.at("entries")] = value(row, "bytes");
  }
  EXPECT_GT(bytes["l1/8/3/3"], bytes["l1/8/3/0"]);  // residual entries cost bytes

  const Csv relighting = read_csv(out / "relighting.csv");
  EXPECT_EQ(
      relighting.columns,
      (std::vector<std::string>{"method", "clusters", "terms", "cap", "frames", "frames_per_second",
                                "kernel_ms", "relit_error", "error_masked", "device"}));
  EXPECT_EQ(relighting.rows.size(), 2u * 3);  // l1 and cpca at caps 0, 1, 3
  std::map<std::string, double> relit;  // method/cap -> relit_error
  for (const auto& row : relighting.rows) {
    EXPECT_GT(value(row, "frames_per_second"), 0);
    EXPECT_GT(value(row, "relit_error"), 0);
    EXPECT_EQ(row.at("clusters"), "8");
    EXPECT_EQ(row.at("terms"), "3");
    relit[row.at("method") + "/" + row.at("cap")] = value(row, "relit_error");
  }
  // The L1 fit relights far better than clustered PCA under the same lights (CPCA's relit error
  // is near 1 on this 40x32 scene); the error falls as the cap admits more entries.
  for (const std::string cap : {"0", "1", "3"}) {
    EXPECT_LT(relit["l1/" + cap], 0.5);
    EXPECT_LT(relit["l1/" + cap], 0.5 * relit["cpca/" + cap]) << "cap " << cap;
  }
  EXPECT_LT(relit["l1/3"], relit["l1/1"]);
  EXPECT_LT(relit["l1/1"], relit["l1/0"]);

  const Csv times = read_csv(out / "compression_time.csv");
  EXPECT_EQ(times.columns,
            (std::vector<std::string>{"method", "clusters", "terms", "refit_for", "seconds",
                                      "refit_seconds", "iterations", "clusters_used"}));
  EXPECT_EQ(times.rows.size(), 4u * (3 + 2));
  for (const auto& row : times.rows) EXPECT_GT(value(row, "seconds"), 0);

  const NpyMatrix difference = read_npy_matrix(out / "error_difference.npy");
  EXPECT_EQ(difference.values.rows(), 32);
  EXPECT_EQ(difference.values.cols(), 40);
  std::size_t finite = 0;
  for (Eigen::Index v = 0; v < difference.values.size(); ++v)
    finite += std::isfinite(difference.values.data()[v]);
  EXPECT_GT(finite, 100u);

  std::ifstream summary_file(out / "eval.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["settings"]["primary"], "8x3");
  EXPECT_EQ(summary["classes"]["diffuse"].get<int>() +
                summary["classes"]["specular_or_shadowed"].get<int>(),
            summary["field"]["stored_functions"].get<int>());
  // The full sphere of lights has both: the clamped fit follows the spheres' diffuse parts and
  // their attached shadows, not the highlights and the ground's cast shadows.
  EXPECT_GT(summary["classes"]["diffuse"].get<int>(), 100);
  EXPECT_GT(summary["classes"]["specular_or_shadowed"].get<int>(), 100);
  EXPECT_EQ(summary["configurations"].size(), 4u);
  EXPECT_TRUE(summary["configurations"][3]["error_at_0_entries"].contains("l1-refit"));

  for (const std::string name :
       {"relit_reference.png", "relit_l1.png", "relit_cpca.png", "relit_l1-refit.png",
        "difference10_l1.png", "difference10_cpca.png"}) {
    const Image image = read_image(out / name);
    EXPECT_EQ(image.width, 40) << name;
    EXPECT_EQ(image.height, 32) << name;
  }
  ASSERT_EQ(summary["files"]["plots"].size(), 8u);
  for (const auto& plot : summary["files"]["plots"]) {
    const Image image = read_image(out / plot.get<std::string>());
    EXPECT_GT(image.width, 300) << plot;
    // Something is drawn: the plot is not one flat colour.
    const auto [lowest, highest] = std::minmax_element(image.pixels.begin(), image.pixels.end());
    EXPECT_LT(*lowest + 0.3f, *highest) << plot;
  }
  EXPECT_TRUE(fs::exists(out / "plot_eval.py"));
}

TEST_F(EvalCommand, RefusesBadSettingsNamingThem) {
  testing::TempDir temp;
  const std::string base = "eval " + scene().string() + " -o " + (temp / "e").string() + " ";
  auto run = testing::run_relume(base + "--methods l1,pca");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, ::testing::HasSubstr("'pca'"));
  run = testing::run_relume(base + "--entries 0,-2");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, ::testing::HasSubstr("-2"));
  run = testing::run_relume(base + "--terms 60");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, ::testing::HasSubstr("--terms 60"));
  run = testing::run_relume(base + "--primary 9x9");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, ::testing::HasSubstr("9x9"));
}

TEST_F(EvalCommand, CompressWritesAClusteredPcaContainerThatRelights) {
  testing::TempDir temp;
  const auto compress = testing::run_relume(
      "compress -q " + scene().string() + " -o " + (temp / "c.relume").string() +
      " --method cpca --clusters 8 --terms 3 --residual 2 --threads 2 --report " +
      (temp / "r.json").string());
  ASSERT_EQ(compress.exit_code, 0) << compress.output;
  std::ifstream report_file(temp / "r.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  EXPECT_EQ(report["parameters"]["method"], "cpca");
  EXPECT_EQ(report["parameters"]["pca_centering"], "none");
  EXPECT_GT(report["error_masked"].get<double>(), 0);
  EXPECT_LT(report["error_masked"].get<double>(), 0.2);
  EXPECT_EQ(report["assignment_device"], "cpu");
  const auto sky = testing::run_relume("sky -q -o " + (temp / "sky.exr").string());
  ASSERT_EQ(sky.exit_code, 0) << sky.output;
  const auto relight =
      testing::run_relume("relight -q " + (temp / "c.relume").string() + " --env " +
                          (temp / "sky.exr").string() + " -o " + (temp / "relit.exr").string());
  ASSERT_EQ(relight.exit_code, 0) << relight.output;
  EXPECT_EQ(read_image(temp / "relit.exr").width, 40);
  const auto bad = testing::run_relume("compress -q " + scene().string() + " -o " +
                                       (temp / "d.relume").string() + " --method svd");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_THAT(bad.output, ::testing::HasSubstr("'svd'"));
  EXPECT_FALSE(fs::exists(temp / "d.relume"));
}

}  // namespace
}  // namespace relume
