// Tests of streamed compression (compress/streamed_compression.hpp) and its parts: the memory
// plan, the float16 scratch store, the report's errors merged over strips, and the streamed result
// itself, which does not depend on the strip height and stores what the in-memory run stores.
#include "compress/streamed_compression.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <relume/error.hpp>

#include "compress/field_errors.hpp"
#include "compress/scratch_rows.hpp"
#include "model/compressed_field_rows.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

// A rendered 48x40 scene of 24 lights, written once for the suite.
class StreamedRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir;
    const auto synth = testing::run_relume("-q synth -o '" + (*dir_ / "scene").string() +
                                           "' --size 48x40 --lights 24 --samples 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }
  static void TearDownTestSuite() { delete dir_; }

  static CompressionOptions options() {
    CompressionOptions options;
    options.clustering.clusters = 8;
    options.clustering.terms = 3;
    options.clustering.threads = 2;
    options.clustering.quiet = true;
    options.residual.entries = 2;
    options.refine_iterations = options.clustering.max_iterations;
    return options;
  }

  static CompressionPlan plan(int strip_rows, std::size_t sample_rows) {
    CompressionPlan plan;
    plan.streamed = true;
    plan.strip_rows = strip_rows;
    plan.sample_rows = sample_rows;
    plan.quantization_rows = 1000;
    plan.scratch_folder = *dir_ / "scratch";
    return plan;
  }

  static StreamedCompression compress(const CompressionPlan& plan, CompressionStats& stats,
                                      const CompressionOptions& options = StreamedRun::options()) {
    FieldStripReader reader(*dir_ / "scene", FieldLoadOptions{});
    StreamedTrace trace;
    return compress_streamed(reader, options, plan, stats, trace, "test.scratch");
  }

  static testing::TempDir* dir_;
};

testing::TempDir* StreamedRun::dir_ = nullptr;

TEST_F(StreamedRun, TheResultDoesNotDependOnTheStripHeight) {
  CompressionStats a_stats, b_stats;
  const CompressedField a = compress(plan(3, 2000), a_stats).field;
  const CompressedField b = compress(plan(7, 2000), b_stats).field;
  EXPECT_EQ(a.stored_function, b.stored_function);
  EXPECT_EQ(a.cluster, b.cluster);
  EXPECT_TRUE(a.weights == b.weights);
  EXPECT_EQ(a.bases, b.bases);
  EXPECT_EQ(a.residual.values, b.residual.values);
  EXPECT_EQ(a.dark_pixels, b.dark_pixels);
  EXPECT_EQ(a.dark, b.dark);
  EXPECT_EQ(a_stats.stored_rows, b_stats.stored_rows);
  for (std::size_t level = 0; level < a_stats.sparseness.size(); ++level)
    EXPECT_NEAR(a_stats.sparseness[level], b_stats.sparseness[level], 1e-12);
  EXPECT_TRUE(fs::is_empty(*dir_ / "scratch")) << "the scratch file is removed";
}

// The streamed run stores the same functions, dark pixels and dark model as the in-memory one,
// and its quantization sample holds the original rows it names. (Its error against the in-memory
// run's is compared by tests/apps/streamed_compress_test.cpp, over seeds.)
TEST_F(StreamedRun, StoresWhatTheInMemoryRunStores) {
  const ReflectanceField field = load_field(*dir_ / "scene");
  CompressionStats memory_stats, streamed_stats;
  const CompressedField in_memory = compress_field(field, options(), memory_stats);
  const std::size_t rows = memory_stats.stored_rows;
  const StreamedCompression streamed = compress(plan(5, rows / 3), streamed_stats);
  EXPECT_EQ(streamed_stats.stored_rows, rows);
  EXPECT_EQ(streamed_stats.dark_pixels, memory_stats.dark_pixels);
  EXPECT_EQ(streamed_stats.all_zero, memory_stats.all_zero);
  EXPECT_EQ(streamed_stats.outside_mask, memory_stats.outside_mask);
  EXPECT_EQ(streamed.field.stored_function, in_memory.stored_function);
  EXPECT_EQ(streamed.field.dark_pixels, in_memory.dark_pixels);
  EXPECT_EQ(streamed.field.mask, in_memory.mask);
  ASSERT_EQ(streamed.field.dark.size(), in_memory.dark.size());
  for (std::size_t v = 0; v < in_memory.dark.size(); ++v)
    EXPECT_NEAR(streamed.field.dark[v], in_memory.dark[v], 1e-6f);
  EXPECT_LT(relative_error(field, streamed.field, true).mean, 0.05);

  // The quantization's sample: whole pixel rows of the original, where it says.
  ASSERT_FALSE(streamed.sample_rows.empty());
  const Eigen::Index row_functions = Eigen::Index(field.width) * field.channels;
  Eigen::Index at = 0;
  for (const auto& [first, count] : streamed.sample_rows) {
    EXPECT_TRUE(streamed.original_sample.values.middleRows(at, count * row_functions) ==
                field.values.middleRows(first * row_functions, count * row_functions));
    at += count * row_functions;
  }
  EXPECT_EQ(at, streamed.original_sample.values.rows());
}

TEST_F(StreamedRun, ErrorsMergedOverStripsEqualTheWholeFieldsErrors) {
  const ReflectanceField field = load_field(*dir_ / "scene");
  CompressionStats stats;
  CompressionOptions lossy = options();
  lossy.residual.entries = 0;
  const CompressedField compressed = compress_field(field, lossy, stats);
  std::vector<std::uint8_t> psnr_mask(std::size_t(field.pixels()), 0);
  for (std::size_t q = 0; q < psnr_mask.size(); q += 3) psnr_mask[q] = 1;
  const FieldErrors whole = measure_field_errors(field, compressed, 6, 1.0, psnr_mask, 2);
  FieldErrors merged;
  const int strip_rows = 7;
  for (int y = 0; y < field.height; y += strip_rows) {
    const int rows = std::min(strip_rows, field.height - y);
    ReflectanceField strip;
    append_field_rows(strip, field, y, rows);
    const std::vector<std::uint8_t> strip_mask(
        psnr_mask.begin() + std::ptrdiff_t(y) * field.width,
        psnr_mask.begin() + std::ptrdiff_t(y + rows) * field.width);
    merge_field_errors(
        merged,
        measure_field_errors(strip, compressed_rows(compressed, y, rows), 6, 1.0, strip_mask, 2),
        std::int64_t(y) * field.width * field.channels);
  }
  EXPECT_NEAR(merged.all.mean, whole.all.mean, 1e-12);
  EXPECT_EQ(merged.all.functions_averaged, whole.all.functions_averaged);
  EXPECT_EQ(merged.all.zero_energy_skipped, whole.all.zero_energy_skipped);
  EXPECT_NEAR(merged.masked.mean, whole.masked.mean, 1e-12);
  ASSERT_EQ(merged.masked_by_prefix.size(), whole.masked_by_prefix.size());
  for (std::size_t i = 0; i < whole.masked_by_prefix.size(); ++i)
    EXPECT_NEAR(merged.masked_by_prefix[i].second.mean, whole.masked_by_prefix[i].second.mean,
                1e-12);
  EXPECT_EQ(merged.per_light.largest, whole.per_light.largest);
  EXPECT_EQ(merged.per_light.function, whole.per_light.function);
  EXPECT_EQ(merged.per_light.light, whole.per_light.light);
  EXPECT_NEAR(merged.per_light.mean_of_largest, whole.per_light.mean_of_largest, 1e-12);
  for (std::size_t level = 0; level < whole.per_light.functions_above.size(); ++level)
    EXPECT_NEAR(merged.per_light.functions_above[level], whole.per_light.functions_above[level],
                1e-12);
  EXPECT_EQ(merged.per_light.negative_values, whole.per_light.negative_values);
  EXPECT_EQ(merged.per_light.most_negative, whole.per_light.most_negative);
  EXPECT_NEAR(merged.psnr.whole_frame, whole.psnr.whole_frame, 1e-9);
  EXPECT_NEAR(merged.psnr.masked, whole.psnr.masked, 1e-9);
  EXPECT_GT(whole.psnr.whole_frame, 20) << "finite and meaningful";
}

TEST_F(StreamedRun, ThePlanStaysInMemoryWhenTheFieldFitsAndRefusesWhenNothingFits) {
  FieldStripReader reader(*dir_ / "scene", FieldLoadOptions{});
  const ReflectanceField& header = reader.header();
  const std::uint64_t field_bytes = std::uint64_t(48) * 40 * 3 * 24 * 4;
  const CompressionPlan roomy =
      plan_compression(header, options(), 100 * field_bytes, "test", 2, *dir_ / "scratch");
  EXPECT_FALSE(roomy.streamed);
  EXPECT_EQ(roomy.field_bytes, field_bytes);
  EXPECT_GE(roomy.in_memory_bytes, 2 * field_bytes);

  const CompressionPlan tight =
      plan_compression(header, options(), field_bytes, "test", 2, *dir_ / "scratch");
  EXPECT_TRUE(tight.streamed);
  EXPECT_GE(tight.strip_rows, 1);
  EXPECT_LT(tight.strip_rows, 40);
  EXPECT_GE(tight.sample_rows, 16u * 8);
  EXPECT_NE(tight.describe().find("streamed"), std::string::npos);

  const std::string refusal = testing::error_message(
      [&] { plan_compression(header, options(), 1000, "test", 2, *dir_ / "scratch"); });
  EXPECT_NE(refusal.find("cannot hold even a one-row strip"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("1000 bytes"), std::string::npos) << refusal;
}

// The plan for a side x side x 253 RGB field header whose first `inside` pixels are inside its
// mask, compressed as the scale benchmark does (64 clusters, 4 terms, 12 residual entries) with
// --memory-limit 3G, by one process or several ranks.
CompressionPlan benchmark_plan_under_3g(int side, std::size_t inside, bool several_ranks = false) {
  ReflectanceField header;
  header.width = side;
  header.height = side;
  header.channels = 3;
  header.values.resize(0, 253);
  header.mask.assign(std::size_t(header.pixels()), 0);
  std::fill_n(header.mask.begin(), inside, std::uint8_t(1));
  CompressionOptions options;
  options.clustering.clusters = 64;
  options.clustering.terms = 4;
  options.residual.entries = 12;
  return plan_compression(header, options, std::uint64_t(3) << 30, "test", 2, "scratch",
                          several_ranks);
}

// A roomy budget for a large field still reads it in strips of at most 16 MiB of values (the
// passes' blocks are as large): larger arrays are mapped and faulted in afresh at every
// allocation, which made the 1280 x 1280 x 253 passes several times slower per row.
TEST(CompressionPlan, StripsStaySmallUnderALargeBudget) {
  const CompressionPlan plan = benchmark_plan_under_3g(1280, 1280 * 1280);
  ASSERT_TRUE(plan.streamed);
  const std::uint64_t strip_bytes = std::uint64_t(plan.strip_rows) * 1280 * 3 * 253 * 4;
  EXPECT_LE(strip_bytes, std::uint64_t(16) << 20);
  EXPECT_GT(strip_bytes, std::uint64_t(8) << 20) << "as tall as the cap allows: "
                                                 << plan.strip_rows << " rows";
}

// Streamed, the compressed field is built in place and quantized in place: the plan counts it
// once, beside the container encoder's byte sections (here 4.5 million functions, under half the
// budget, so it stays in memory).
TEST(CompressionPlan, CountsTheCompressedFieldOnce) {
  const CompressionPlan plan = benchmark_plan_under_3g(2560, 1'500'000);
  ASSERT_TRUE(plan.streamed);
  EXPECT_FALSE(plan.compressed_on_disk);
  const std::uint64_t compressed = std::uint64_t(1'500'000) * 3 * (4 * 4 + 12 * 8 + 8);
  EXPECT_GE(plan.model_bytes, compressed + compressed / 4 * 3);
  EXPECT_LT(plan.model_bytes, 2 * compressed);
  EXPECT_GE(plan.sample_rows, 16u * 64);
}

// The scale benchmark's 2560 x 2560 x 253 field (10.8 million functions inside its mask): held,
// its compressed field would take most of 3 GB, so it is built on disk and only the passes'
// state per row is held; several ranks plan alike (each holds its band's strips on disk).
TEST(CompressionPlan, PutsTheCompressedFieldOnDiskWhenItWouldTakeHalfTheBudget) {
  const CompressionPlan plan = benchmark_plan_under_3g(2560, 3'610'000);
  ASSERT_TRUE(plan.streamed);
  EXPECT_TRUE(plan.compressed_on_disk);
  const std::uint64_t functions = std::uint64_t(3'610'000) * 3;
  const std::uint64_t compressed = functions * (4 * 4 + 12 * 8 + 8);
  EXPECT_LT(plan.model_bytes, compressed / 2);
  EXPECT_GE(plan.scratch_bytes, functions * 253 * 2 + compressed);
  EXPECT_NE(plan.describe().find("the compressed field on disk"), std::string::npos);
  const CompressionPlan ranks = benchmark_plan_under_3g(2560, 3'610'000, true);
  EXPECT_TRUE(ranks.compressed_on_disk);
  EXPECT_EQ(ranks.model_bytes, plan.model_bytes);
  EXPECT_EQ(ranks.sample_rows, plan.sample_rows);
  EXPECT_EQ(ranks.strip_rows, plan.strip_rows);
}

TEST(ScratchRows, RowsComeBackAtHalfPrecisionMoveExactlyAndTheFileGoes) {
  testing::TempDir dir;
  WorkingRows rows;
  rows.values.resize(5, 7);
  for (int v = 0; v < rows.values.size(); ++v) rows.values.data()[v] = float(v % 5) - 1.7f;
  rows.values.rowwise().normalize();
  rows.norms = {1, 2, 3, 4, 5};
  fs::path file;
  {
    ScratchRows scratch(dir / "scratch", "out.relume.scratch", 7);
    scratch.append(rows);
    scratch.append(rows);
    file = scratch.path();
    EXPECT_TRUE(fs::exists(file));
    EXPECT_EQ(scratch.rows(), 10u);
    EXPECT_EQ(scratch.bytes(), 10u * 7 * 2);
    EXPECT_EQ(fs::file_size(file), scratch.bytes());
    const WorkingRows back = scratch.read(6, 3);
    for (int r = 0; r < 3; ++r) {
      EXPECT_EQ(back.norms[r], rows.norms[r + 1]);
      EXPECT_NEAR(back.values.row(r).norm(), 1.0f, 1e-6f);
      for (int i = 0; i < 7; ++i) EXPECT_NEAR(back.values(r, i), rows.values(r + 1, i), 1e-3f);
    }
    EXPECT_THROW(scratch.read(8, 3), Error);
    // Blocks move rows to another store bit for bit (as ranks move them to balance their bands).
    ScratchRows moved(dir / "scratch", "out.relume.scratch.moved", 7);
    moved.append_block(scratch.read_block(6, 3));
    moved.append_block(scratch.read_block(0, 2));
    EXPECT_EQ(moved.read_block(0, 5).halves, [&] {
      std::vector<std::uint16_t> halves = scratch.read_block(6, 3).halves;
      const std::vector<std::uint16_t> first = scratch.read_block(0, 2).halves;
      halves.insert(halves.end(), first.begin(), first.end());
      return halves;
    }());
    EXPECT_EQ(moved.read_block(3, 2).norms, (std::vector<float>{1, 2}));
    ScratchBlock short_block = scratch.read_block(0, 2);
    short_block.halves.pop_back();
    EXPECT_THROW(moved.append_block(short_block), Error);
    EXPECT_EQ(moved.rows(), 5u);
  }
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace relume
