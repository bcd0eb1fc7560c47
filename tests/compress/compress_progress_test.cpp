// Tests of the public compress()'s progress callback and interruption: the callback hears the
// phases on the calling thread with fractions from 0 to 1; a callback that requests an
// interruption, or throws Interrupted, stops the compress with relume::Interrupted, and once the
// request is cleared the same compress gives the same result as an uninterrupted one.
#include <gtest/gtest.h>

#include <relume/compress.hpp>
#include <relume/error.hpp>
#include <set>
#include <thread>

#include "core/interruption.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

ReflectanceField small_scene() {
  SynthOptions synth;
  synth.width = 32;
  synth.height = 24;
  synth.lights = 40;
  synth.samples_per_axis = 1;
  synth.threads = 2;
  return render_synthetic_field(synth);
}

CompressOptions small_options() {
  CompressOptions options;
  options.clusters = 6;
  options.terms = 3;
  options.residual = relume::ResidualBudget{4};
  options.assign = "cpu";  // the C++ path reports every assignment's rows
  options.threads = 2;
  return options;
}

TEST(CompressProgress, HearsEveryPhaseOnTheCallingThread) {
  const ReflectanceField field = small_scene();
  CompressOptions options = small_options();
  std::set<std::string> phases;
  std::vector<double> iteration_fractions;
  bool other_thread = false;
  const std::thread::id caller = std::this_thread::get_id();
  options.progress = [&](const std::string& phase, double fraction) {
    phases.insert(phase);
    if (phase == "compress: iterations") iteration_fractions.push_back(fraction);
    other_thread = other_thread || std::this_thread::get_id() != caller;
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
  };
  compress(field, options);
  EXPECT_FALSE(other_thread);
  EXPECT_TRUE(phases.count("compress: iterations"));
  EXPECT_TRUE(phases.count("compress: iteration 0, assigning")) << "the first assignment";
  ASSERT_GE(iteration_fractions.size(), 2u);
  EXPECT_EQ(iteration_fractions.front(), 0.0);
  EXPECT_EQ(iteration_fractions.back(), 1.0);
}

TEST(CompressProgress, RequestedInterruptionThrowsInterruptedAndClears) {
  const ReflectanceField field = small_scene();
  clear_interruption();
  const CompressedField whole = compress(field, small_options());

  CompressOptions options = small_options();
  int calls = 0;
  options.progress = [&](const std::string&, double) {
    if (++calls == 1) request_interruption();
  };
  EXPECT_THROW(compress(field, options), Interrupted);
  EXPECT_LE(calls, 3) << "the compress went on after the request";
  clear_interruption();

  options.progress = {};
  const CompressedField again = compress(field, options);
  EXPECT_EQ(again.cluster, whole.cluster);
  EXPECT_EQ(again.bases, whole.bases);
  EXPECT_EQ(again.residual.values, whole.residual.values);
}

TEST(CompressProgress, CallbackThatThrowsStopsTheCompress) {
  const ReflectanceField field = small_scene();
  CompressOptions options = small_options();
  options.progress = [](const std::string& phase, double) {
    if (phase == "compress: iteration 0, assigning") throw Interrupted();
  };
  EXPECT_THROW(compress(field, options), Interrupted);
  EXPECT_FALSE(interruption_requested());
}

}  // namespace
}  // namespace relume
