// Tests of the evaluation of one field (eval/evaluation.hpp) on a small synthetic scene: its
// settings are resolved and refused as `relume eval` names them; every run of the grid is made
// and measured, with numbers that hold together (keeping every residual entry leaves no error,
// errors fall with entries, the ratios are clustered PCA's error over the method's, the class
// means average to the mean over all functions, clustered PCA's residual entries are at most the
// function's norm, the per-pixel map covers exactly the pixels with a stored function, bytes
// grow with entries); the relighting, the hooks, the progress and an interruption.
#include "eval/evaluation.hpp"

#include <gtest/gtest.h>

#include <map>
#include <relume/error.hpp>
#include <set>

#include "core/interruption.hpp"
#include "lighting/environment_map.hpp"
#include "support/test_support.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

constexpr int lights = 40;

ReflectanceField small_scene() {
  SynthOptions synth;
  synth.width = 32;
  synth.height = 24;
  synth.lights = lights;
  synth.samples_per_axis = 1;
  synth.threads = 2;
  return render_synthetic_field(synth);
}

EnvironmentMap sky() {
  return make_environment_map(render_sky({}), EnvironmentLayout::latlong, "the built-in sky");
}

// A 2 x 2 grid; `lights` entries keep every residual entry.
EvaluationOptions small_grid() {
  EvaluationOptions options;
  options.clusters = {6, 3};
  options.terms = {3, 2};
  options.entries = {2, 0, lights, 2};
  options.refit_entries = {2, 0};
  options.compare_entries = 2;
  options.frames = 1;
  options.timed_calls = 1;
  options.assign = "cpu";
  options.threads = 2;
  return options;
}

std::string key(const EvalRun& run) {
  return run.method + "/" + std::to_string(run.clusters_asked) + "x" + std::to_string(run.terms) +
         (run.budget >= 0 ? "/" + std::to_string(run.budget) : "");
}

TEST(EvaluationOptions, ResolvedAsTheEvaluationRunsThem) {
  const EvaluationOptions options = resolve_evaluation_options(small_grid());
  EXPECT_EQ(options.clusters, (std::vector<int>{3, 6}));
  EXPECT_EQ(options.terms, (std::vector<int>{2, 3}));
  EXPECT_EQ(options.entries, (std::vector<int>{0, 2, lights}));
  EXPECT_EQ(options.refit_entries, (std::vector<int>{0, 2}));
  EXPECT_EQ(options.rate_entries, options.entries);
  EXPECT_EQ(options.primary_clusters, 6);
  EXPECT_EQ(options.primary_terms, 3);

  EvaluationOptions without_refits = small_grid();
  without_refits.methods = {"cpca", "l1"};
  without_refits.refit_entries = {-1};  // not checked: no l1-refit run uses them
  EXPECT_TRUE(resolve_evaluation_options(without_refits).refit_entries.empty());
}

TEST(EvaluationOptions, RefusedNamingTheOptionAndValue) {
  const auto refusal = [](const std::function<void(EvaluationOptions&)>& change) {
    EvaluationOptions options = small_grid();
    change(options);
    return testing::error_message([&] { resolve_evaluation_options(options); });
  };
  EXPECT_THAT(refusal([](auto& o) { o.methods = {"l1", "pca"}; }), ::testing::HasSubstr("'pca'"));
  EXPECT_THAT(refusal([](auto& o) {
                o.methods = {"l1", "cpca-mean"};
              }),
              ::testing::HasSubstr("must include l1 and cpca"));
  EXPECT_THAT(refusal([](auto& o) {
                o.entries = {0, -2};
              }),
              ::testing::HasSubstr("--entries value -2"));
  EXPECT_THAT(refusal([](auto& o) { o.clusters = {}; }), ::testing::HasSubstr("--clusters"));
  EXPECT_THAT(refusal([](auto& o) { o.assign = "gpu"; }), ::testing::HasSubstr("'gpu'"));
  EXPECT_THAT(refusal([](auto& o) {
                o.primary_clusters = 5;
                o.primary_terms = 3;
              }),
              ::testing::HasSubstr("--primary '5x3'"));
}

// One evaluation of the small scene, shared by the suite.
class Evaluation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    field_ = new ReflectanceField(small_scene());
    EvaluationOptions options = small_grid();
    options.on_classes = [](std::size_t stored, const FunctionClasses& classes) {
      told_stored_ = stored;
      EXPECT_EQ(classes.diffuse.size(), stored);
    };
    options.on_run = [](const EvalRun& run) { told_runs_.push_back(key(run)); };
    options.on_relit = [](const RelightingRow&) { ++told_relit_; };
    result_ = new EvaluationResult(evaluate_field(*field_, sky(), options));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete field_;
  }

  static std::size_t run_index(const std::string& wanted) {
    for (std::size_t i = 0; i < result_->runs.size(); ++i)
      if (key(result_->runs[i]) == wanted) return i;
    ADD_FAILURE() << "no run " << wanted;
    return 0;
  }
  // error_all of a run at a number of entries.
  static double error(const std::string& run, int entries) {
    const std::size_t index = run_index(run);
    for (const ErrorPoint& point : result_->errors)
      if (point.run == index && point.entries == entries) return point.error.all;
    ADD_FAILURE() << "no error of " << run << " at " << entries << " entries";
    return NAN;
  }

  static ReflectanceField* field_;
  static EvaluationResult* result_;
  static std::size_t told_stored_;
  static std::vector<std::string> told_runs_;
  static int told_relit_;
};

ReflectanceField* Evaluation::field_ = nullptr;
EvaluationResult* Evaluation::result_ = nullptr;
std::size_t Evaluation::told_stored_ = 0;
std::vector<std::string> Evaluation::told_runs_;
int Evaluation::told_relit_ = 0;

TEST_F(Evaluation, StoresTheMaskedNonZeroFunctionsAndClassifiesThem) {
  std::size_t stored = 0;
  for (std::int64_t p = 0; p < field_->functions(); ++p)
    stored += field_->mask[std::size_t(p / field_->channels)] && field_->values.row(p).any();
  EXPECT_GT(stored, 500u);
  EXPECT_EQ(result_->stored_functions, stored);
  EXPECT_EQ(told_stored_, stored);
  EXPECT_EQ(result_->dark_pixels, 0u);  // a float render has no noise floor
  EXPECT_EQ(result_->classes.diffuse.size(), stored);
  EXPECT_GT(result_->classes.diffuse_count, 0u);
  EXPECT_LT(result_->classes.diffuse_count, stored);
  EXPECT_EQ(result_->assignment, "cpu");
}

TEST_F(Evaluation, MakesEveryRunOfTheGridInOrder) {
  std::vector<std::string> expected;
  for (const std::string configuration : {"3x2", "3x3", "6x2", "6x3"})
    for (const std::string run : {"l1/", "cpca/", "cpca-mean/", "l1-refit/", "l1-refit/"})
      expected.push_back(run + configuration);
  for (std::size_t r = 3; r < expected.size(); r += 5) {
    expected[r] += "/0";
    expected[r + 1] += "/2";
  }
  std::vector<std::string> made;
  for (const EvalRun& run : result_->runs) {
    made.push_back(key(run));
    EXPECT_GT(run.seconds, 0) << key(run);
    EXPECT_GE(run.model.clusters, 1) << key(run);
    EXPECT_LE(run.model.clusters, run.clusters_asked) << key(run);
  }
  EXPECT_EQ(made, expected);
  EXPECT_EQ(told_runs_, expected);
}

TEST_F(Evaluation, ErrorsVanishWithEveryEntryAndFallWithEntries) {
  // 4 configurations x (3 dynamic runs x 3 entries + 2 refits).
  EXPECT_EQ(result_->errors.size(), 4u * (3 * 3 + 2));
  const FunctionClasses& classes = result_->classes;
  const double diffuse = double(classes.diffuse_count);
  const double specular = double(result_->stored_functions - classes.diffuse_count);
  for (const ErrorPoint& point : result_->errors) {
    const SubsetErrors& e = point.error;
    EXPECT_NEAR(e.all * (diffuse + specular), e.diffuse * diffuse + e.specular * specular,
                1e-9 * (diffuse + specular));
  }
  for (const std::string configuration : {"3x2", "3x3", "6x2", "6x3"})
    for (const std::string method : {"l1", "cpca", "cpca-mean"}) {
      const std::string run = method + "/" + configuration;
      EXPECT_GT(error(run, 0), 0.0) << run;
      EXPECT_LT(error(run, 0), 1.0) << run;
      EXPECT_LE(error(run, 2), error(run, 0)) << run;
      EXPECT_NEAR(error(run, lights), 0.0, 1e-12) << run;
    }
  // More terms help; the refit never loses at its budget.
  EXPECT_LT(error("l1/6x3", 0), error("l1/6x2", 0));
  for (const int budget : {0, 2})
    EXPECT_LE(error("l1-refit/6x3/" + std::to_string(budget), budget),
              error("l1/6x3", budget) * (1 + 1e-9));
}

TEST_F(Evaluation, RatiosAreClusteredPcaOverTheMethod) {
  EXPECT_EQ(result_->ratios.size(), 4u * (3 + 2));
  for (const ErrorRatio& ratio : result_->ratios) {
    if (ratio.entries == lights) continue;  // both errors are rounding
    const std::string configuration =
        std::to_string(ratio.clusters) + "x" + std::to_string(ratio.terms);
    const std::string method = ratio.method == "l1-refit" ? "l1-refit/" + configuration + "/" +
                                                                std::to_string(ratio.entries)
                                                          : "l1/" + configuration;
    EXPECT_DOUBLE_EQ(ratio.ratio.all,
                     error("cpca/" + configuration, ratio.entries) / error(method, ratio.entries))
        << method;
  }
}

TEST_F(Evaluation, SparsenessRisesToEveryEntryForClusteredPca) {
  EXPECT_EQ(result_->sparseness.size(), 4u * 3 * 25);
  std::map<std::size_t, std::vector<const SparsenessPoint*>> per_run;
  for (const SparsenessPoint& point : result_->sparseness) per_run[point.run].push_back(&point);
  for (const auto& [run, points] : per_run) {
    EXPECT_EQ(result_->runs[run].budget, -1);
    ASSERT_EQ(points.size(), 25u);
    EXPECT_DOUBLE_EQ(points.front()->threshold, 1e-4);
    EXPECT_DOUBLE_EQ(points.back()->threshold, 1.0);
    for (std::size_t t = 1; t < points.size(); ++t)
      EXPECT_GE(points[t]->fraction, points[t - 1]->fraction);
    // A least-squares residual of a unit row has no entry above 1 (but by rounding).
    if (result_->runs[run].method == "cpca") EXPECT_GT(points.back()->fraction, 0.999);
  }
}

TEST_F(Evaluation, PerPixelDifferenceCoversThePixelsWithAStoredFunction) {
  const ErrorDifference& difference = result_->difference;
  ASSERT_EQ(difference.l1.rows(), 24);
  ASSERT_EQ(difference.l1.cols(), 32);
  EXPECT_EQ(difference.l1_refit.rows(), 24);  // the primary 6x3 has a refit for 2 entries
  std::size_t pixels = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      bool stored = false;
      for (int c = 0; c < field_->channels; ++c)
        stored = stored || field_->values.row(field_->function_index(x, y, c)).any();
      stored = stored && field_->mask[std::size_t(y) * 32 + x];
      pixels += stored;
      EXPECT_EQ(std::isnan(difference.l1(y, x)), !stored) << x << ", " << y;
    }
  EXPECT_EQ(difference.pixels, pixels);
  EXPECT_LE(difference.l1_better, pixels);
}

TEST_F(Evaluation, ContainersCostMoreBytesWithMoreEntries) {
  EXPECT_EQ(result_->rate.size(), 4u * (3 * 3 + 2));
  std::map<std::string, double> bytes;
  for (const RatePoint& point : result_->rate) {
    EXPECT_NEAR(point.bytes_per_pixel * 32 * 24, double(point.bytes), 1e-6);
    EXPECT_NEAR(point.ratio * double(field_->functions()) * lights * 4, double(point.bytes), 1e-6);
    EXPECT_GE(point.error_masked, 0.0);
    EXPECT_GT(point.psnr.masked, 10);
    bytes[key(result_->runs[point.run]) + "@" + std::to_string(point.entries)] =
        double(point.bytes);
  }
  EXPECT_LT(bytes["l1/6x3@0"], bytes["l1/6x3@2"]);
  EXPECT_LT(bytes["l1/6x3@2"], bytes["l1/6x3@40"]);
}

TEST_F(Evaluation, RelightsThePrimaryConfigurationAtEveryCap) {
  const RelightingResult& relit = result_->relighting;
  ASSERT_EQ(relit.rows.size(), 2u * 3);  // l1 and cpca at 0, 2 and 40 entries
  EXPECT_EQ(told_relit_, 2 * 3 + 1);     // and the refit's image
  EXPECT_FALSE(relit.device.empty());
  std::map<std::string, const RelightingRow*> rows;
  for (const RelightingRow& row : relit.rows) {
    rows[row.method + "@" + std::to_string(row.cap)] = &row;
    EXPECT_GT(row.frames_per_second, 0);
    EXPECT_GT(row.relit_error, 0);
  }
  EXPECT_LT(rows["l1@2"]->relit_error, rows["l1@0"]->relit_error);
  EXPECT_LT(rows["l1@2"]->error_masked, rows["l1@0"]->error_masked);
  EXPECT_LT(rows["l1@40"]->error_masked, rows["l1@2"]->error_masked);
  ASSERT_EQ(relit.images.size(), 3u);
  EXPECT_EQ(relit.images[0].first, "l1");
  EXPECT_EQ(relit.images[1].first, "cpca");
  EXPECT_EQ(relit.images[2].first, "l1-refit");
  for (const auto& [method, image] : relit.images) EXPECT_EQ(image.width, 32) << method;
  EXPECT_EQ(relit.reference.height, 24);
}

TEST_F(Evaluation, HeadlinesRepeatTheErrorsOfEachConfiguration) {
  ASSERT_EQ(result_->configurations.size(), 4u);
  const ConfigurationErrors& last = result_->configurations.back();
  EXPECT_EQ(last.clusters, 6);
  EXPECT_EQ(last.terms, 3);
  for (const MethodErrors* at : {&last.without_residual, &last.at_compare_entries}) {
    ASSERT_EQ(at->errors.size(), 4u);
    const std::string names[] = {"l1", "cpca", "cpca-mean", "l1-refit"};
    for (std::size_t m = 0; m < 4; ++m) {
      EXPECT_EQ(at->errors[m].first, names[m]);
      const std::string run = names[m] + "/6x3" + (m == 3 ? "/" + std::to_string(at->entries) : "");
      EXPECT_EQ(at->errors[m].second, error(run, at->entries)) << run;
    }
  }
  EXPECT_EQ(last.at_compare_entries.entries, 2);
}

TEST(EvaluationProgress, HearsEveryStepAndStopsWhenInterrupted) {
  const ReflectanceField field = small_scene();
  EvaluationOptions options = small_grid();
  options.clusters = {3};
  options.terms = {2};
  std::map<std::string, double> last;
  options.progress = [&](const std::string& title, double fraction) { last[title] = fraction; };
  clear_interruption();
  evaluate_field(field, sky(), options);
  for (const std::string title : {"eval: compressing", "eval: measuring errors",
                                  "eval: storing containers", "eval: relighting"}) {
    ASSERT_TRUE(last.count(title)) << title;
    EXPECT_EQ(last[title], 1.0) << title;
  }

  int runs = 0;
  options.on_run = [&](const EvalRun&) {
    if (++runs == 1) request_interruption();
  };
  EXPECT_THROW(evaluate_field(field, sky(), options), Interrupted);
  clear_interruption();
  EXPECT_EQ(runs, 1) << "the grid went on after the request";
}

}  // namespace
}  // namespace relume
