// Tests of the compressed-field relighters: the double-precision CPU reference against a dense
// reconstruction, and every OpenCL relighting kernel (GEMV, residual SpMV, relight, batched
// relight) on PoCL against the reference with fresh random fields and light vectors: residual
// caps of 0, below and above the row lengths, empty rows, unstored functions, odd term and light
// counts, grey fields, the Haar basis, every row-vector width, slice height and head/tail split,
// and quantized fields (int8 / int16 weights and residual values) at every term count.
#include "relight/opencl_relighter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <relume/error.hpp>

#include "model/basis_alignment.hpp"
#include "model/haar_transform.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "relight/compressed_relight_reference.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

RandomFieldShape small_shape(std::uint64_t seed) {
  RandomFieldShape shape;
  shape.width = 32;
  shape.height = 24;
  shape.channels = 3;
  shape.lights = 41;  // odd: the GEMV's 2x2 blocks need a zero-padded light
  shape.clusters = 5;
  shape.terms = 4;
  shape.residual_per_function = 7;
  shape.vary_residual = true;   // rows of 0 to 7 entries, empty rows included
  shape.stored_fraction = 0.8;  // the rest are unstored functions that must relight to 0
  shape.seed = seed;
  return shape;
}

// ||a - b|| / ||b|| over all pixels.
double relative_error(const Image& a, const Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.channels, b.channels);
  double difference = 0, norm = 0;
  for (std::size_t i = 0; i < b.pixels.size(); ++i) {
    difference += std::pow(double(a.pixels[i]) - b.pixels[i], 2);
    norm += std::pow(double(b.pixels[i]), 2);
  }
  return std::sqrt(difference / norm);
}

// Functions without a stored row relight to exactly zero.
void expect_unstored_zero(const CompressedField& field, const Image& image) {
  std::vector<bool> stored(std::size_t(field.functions()), false);
  for (const auto p : field.stored_function) stored[p] = true;
  int checked = 0;
  for (std::size_t p = 0; p < stored.size(); ++p)
    if (!stored[p]) {
      ASSERT_EQ(image.pixels[p], 0.0f) << "unstored function " << p;
      ++checked;
    }
  EXPECT_GT(checked, 0) << "the test field should leave some functions unstored";
}

OpenClContext& pocl() {
  static OpenClContext context(select_opencl_device("portable computing language"));
  return context;
}

constexpr double float_tolerance = 1e-5;  // float32 accumulation against double

TEST(CompressedRelightReference, MatchesTheDenseReconstruction) {
  // Rebuild each stored row R~[p,:] = W[p,:] F^k + (first cap residual entries) densely, then
  // relight it as R~ . I: another order of the same sums.
  const CompressedField field = random_compressed_field(small_shape(1));
  const LightRgb light = random_light_vector(field.lights, 2);
  for (const int cap : {0, 3, all_residual_entries}) {
    const Image image = relight_compressed_reference(field, light, cap);
    std::vector<double> expected(std::size_t(field.functions()), 0.0);
    for (std::size_t s = 0; s < field.stored_rows(); ++s) {
      std::vector<double> row(std::size_t(field.lights), 0.0);
      for (int j = 0; j < field.terms; ++j)
        for (int i = 0; i < field.lights; ++i)
          row[std::size_t(i)] += double(field.weights(Eigen::Index(s), j)) *
                                 field.basis(int(field.cluster[s]))[j * field.lights + i];
      const auto begin = field.residual.row_offsets[s], end = field.residual.row_offsets[s + 1];
      for (auto e = begin; e < end && int(e - begin) < cap; ++e)
        row[field.residual.light_index[e]] += field.residual.values[e];
      const std::uint32_t p = field.stored_function[s];
      for (int i = 0; i < field.lights; ++i)
        expected[p] += row[std::size_t(i)] * light(i, int(p % 3));
    }
    for (std::size_t p = 0; p < expected.size(); ++p)
      ASSERT_NEAR(image.pixels[p], expected[p], 1e-5 * (1 + std::abs(expected[p])))
          << "function " << p << ", cap " << cap;
  }
}

TEST(CompressedRelightReference, ResidualOnlyIsTheDifferenceOfCaps) {
  const CompressedField field = random_compressed_field(small_shape(3));
  const LightRgb light = random_light_vector(field.lights, 4);
  const Image all = relight_compressed_reference(field, light, 4);
  const Image basis = relight_compressed_reference(field, light, 0);
  const Image residual = relight_compressed_reference(field, light, 4, RelightTerms::residual_only);
  for (std::size_t i = 0; i < all.pixels.size(); ++i)
    ASSERT_NEAR(residual.pixels[i], all.pixels[i] - basis.pixels[i], 1e-5);
}

TEST(CompressedRelightReference, RefusesBadInput) {
  CompressedField field = random_compressed_field(small_shape(5));
  LightRgb light = random_light_vector(field.lights, 6);
  EXPECT_THROW(relight_compressed_reference(field, light, -1), Error);
  EXPECT_THROW(relight_compressed_reference(field, random_light_vector(field.lights + 1, 6)),
               Error);
  light(3, 1) = std::nanf("");
  EXPECT_THROW(relight_compressed_reference(field, light), Error);
  field.cluster[0] = std::uint32_t(field.clusters);
  EXPECT_THROW(CompressedRelightReference{field}, Error);
}

TEST(OpenClRelighter, MatchesTheReferenceForEveryResidualCap) {
  const CompressedField field = random_compressed_field(small_shape(10));
  OpenClRelighter relighter(pocl(), field);
  ASSERT_EQ(relighter.widest_residual_row(), 7);
  // 0: basis only; 3: fewer than most rows hold; 7: exactly the widest; 50: more than any.
  for (const int cap : {0, 3, 7, 50, all_residual_entries}) {
    const LightRgb light = random_light_vector(field.lights, 100 + std::uint64_t(cap % 1000));
    const Image expected = relight_compressed_reference(field, light, cap);
    const Image image = relighter.relight(light, cap);
    EXPECT_LT(relative_error(image, expected), float_tolerance) << "cap " << cap;
    expect_unstored_zero(field, image);
  }
}

// Quantized fields relight from their integers (relight_layout.hpp folds the steps into the
// blocks and the light vector): int8 and int16 weights and residual values, alone and together,
// at term counts 1 to 5, single and batched, against the reference on the same field.
TEST(OpenClRelighter, QuantizedFieldsRelightFromTheirIntegersAtEveryPrecision) {
  // Bytes per stored value: 4 float, 2 int16, 1 int8.
  struct Precision {
    int weight_bytes, residual_bytes;
  };
  const Precision precisions[] = {{1, 4}, {2, 4}, {4, 1}, {4, 2}, {1, 2}, {2, 1}};
  // The step that puts the largest |value| at 100 (int8) or 20000 (int16); 0 keeps floats.
  auto step_for = [](float largest, int bytes) {
    return bytes == 4 ? 0.0f : largest / (bytes == 1 ? 100.0f : 20000.0f);
  };
  // Every precision and every term count, each kernel build once (PoCL builds are slow): terms
  // 1 to 5 with the precisions in turn, and the last precision with 3 terms.
  for (std::size_t config = 0; config < std::size(precisions); ++config) {
    const Precision& precision = precisions[config];
    const int terms = config < 5 ? int(config) + 1 : 3;
    RandomFieldShape shape = small_shape(300 + std::uint64_t(terms));
    shape.terms = terms;
    CompressedField field = random_compressed_field(shape);
    align_cluster_bases(field);
    float largest_residual = 0;
    for (float v : field.residual.values)
      largest_residual = std::max(largest_residual, std::abs(v));
    const float weight_step = step_for(field.weights.cwiseAbs().maxCoeff(), precision.weight_bytes);
    const float residual_step = step_for(largest_residual, precision.residual_bytes);
    field = quantize_values(field, {weight_step, residual_step, 0});
    OpenClRelighterOptions options;
    options.max_batch = 4;
    OpenClRelighter relighter(pocl(), field, options);
    const std::string what = std::to_string(terms) + " terms, " +
                             std::to_string(precision.weight_bytes) + "-byte weights, " +
                             std::to_string(precision.residual_bytes) + "-byte residual";
    std::vector<LightRgb> lights;
    for (int b = 0; b < 4; ++b)
      lights.push_back(random_light_vector(field.lights, 700 + std::uint64_t(terms * 10 + b)));
    for (const int cap : {0, 3, all_residual_entries}) {
      const Image single = relighter.relight(lights[0], cap);
      EXPECT_LT(relative_error(single, relight_compressed_reference(field, lights[0], cap)),
                float_tolerance)
          << what << ", cap " << cap;
      expect_unstored_zero(field, single);
      const std::vector<Image> batch = relighter.relight_batch(lights, cap);
      for (int b = 0; b < 4; ++b)
        EXPECT_LT(relative_error(batch[std::size_t(b)],
                                 relight_compressed_reference(field, lights[std::size_t(b)], cap)),
                  float_tolerance)
            << what << ", cap " << cap << ", frame " << b;
    }
    // The products come back in field units whatever the steps folded into the blocks.
    const LightRgb& light = lights[1];
    const std::vector<double> expected =
        cluster_light_products(field, light_in_field_basis(field, light));
    const std::vector<float> products = relighter.cluster_products(light);
    ASSERT_EQ(products.size(), expected.size());
    for (std::size_t i = 0; i < products.size(); ++i)
      EXPECT_NEAR(products[i], expected[i], 1e-4 * (1 + std::abs(expected[i]))) << what;
    // The kernels read the integers, in the narrowest type that holds them.
    EXPECT_EQ(relighter.weight_bytes(), precision.weight_bytes) << what;
    EXPECT_EQ(relighter.residual_value_bytes(), precision.residual_bytes) << what;
  }
}

// HDR maps reach 1.4e5 : 1 (Grace Cathedral) and stored rows span many decades of brightness:
// float32 accumulation must stay accurate for the dim rows too, not only over the whole image.
TEST(OpenClRelighter, ExtremeDynamicRangeStaysAccurateAtEveryBrightness) {
  CompressedField field = random_compressed_field(small_shape(12));
  constexpr int decades = 13;  // rows scaled by 1e-6 ... 1e6
  auto exponent_of = [](std::size_t s) { return int(s % decades) - 6; };
  for (std::size_t s = 0; s < field.stored_rows(); ++s) {
    const float scale = std::pow(10.0f, float(exponent_of(s)));
    field.weights.row(Eigen::Index(s)) *= scale;
    for (std::uint32_t k = field.residual.row_offsets[s]; k < field.residual.row_offsets[s + 1];
         ++k)
      field.residual.values[k] *= scale;
  }
  LightRgb light = random_light_vector(field.lights, 13);
  light.row(3) *= 1.4e5f;  // a sun among dim lights
  light.row(17) *= 1e-4f;
  OpenClRelighter relighter(pocl(), field);
  for (const int cap : {0, all_residual_entries}) {
    const Image expected = relight_compressed_reference(field, light, cap);
    const Image image = relighter.relight(light, cap);
    std::vector<double> difference(decades, 0.0), energy(decades, 0.0);
    for (std::size_t s = 0; s < field.stored_rows(); ++s) {
      const std::uint32_t p = field.stored_function[s];
      ASSERT_TRUE(std::isfinite(image.pixels[p])) << "row " << s;
      const int decade = exponent_of(s) + 6;
      difference[decade] += std::pow(double(image.pixels[p]) - expected.pixels[p], 2);
      energy[decade] += std::pow(double(expected.pixels[p]), 2);
    }
    for (int decade = 0; decade < decades; ++decade) {
      ASSERT_GT(energy[decade], 0);
      EXPECT_LT(std::sqrt(difference[decade] / energy[decade]), float_tolerance)
          << "rows scaled by 1e" << decade - 6 << ", cap " << cap;
    }
  }
}

TEST(OpenClRelighter, ClusterProductsMatchTheReference) {
  const CompressedField field = random_compressed_field(small_shape(11));
  OpenClRelighter relighter(pocl(), field);
  const LightRgb light = random_light_vector(field.lights, 12);
  const std::vector<double> expected =
      cluster_light_products(field, light_in_field_basis(field, light));
  const std::vector<float> products = relighter.cluster_products(light);
  ASSERT_EQ(products.size(), expected.size());
  for (std::size_t i = 0; i < products.size(); ++i)
    ASSERT_NEAR(products[i], expected[i], 1e-5 * (1 + std::abs(expected[i]))) << "product " << i;
  EXPECT_EQ(relighter.last_timing().kernels.size(), 1u);
  EXPECT_EQ(relighter.last_timing().kernels[0].kernel, "gemv");
}

TEST(OpenClRelighter, ResidualSpmvMatchesTheReference) {
  const CompressedField field = random_compressed_field(small_shape(13));
  OpenClRelighter relighter(pocl(), field);
  for (const int cap : {0, 2, all_residual_entries}) {
    const LightRgb light = random_light_vector(field.lights, 14 + std::uint64_t(cap % 100));
    const Image expected =
        relight_compressed_reference(field, light, cap, RelightTerms::residual_only);
    const Image image = relighter.relight_residual(light, cap);
    if (cap == 0) {
      for (const float value : image.pixels) ASSERT_EQ(value, 0.0f);
    } else {
      EXPECT_LT(relative_error(image, expected), float_tolerance) << "cap " << cap;
    }
    EXPECT_EQ(relighter.last_timing().kernel("spmv").kernel, "spmv");
  }
}

TEST(OpenClRelighter, OddTermCountsUseZeroPaddedBlocks) {
  for (const int terms : {1, 3, 5}) {
    RandomFieldShape shape = small_shape(20 + std::uint64_t(terms));
    shape.terms = terms;
    shape.residual_per_function = 4;
    const CompressedField field = random_compressed_field(shape);
    OpenClRelighter relighter(pocl(), field);
    const LightRgb light = random_light_vector(field.lights, 30 + std::uint64_t(terms));
    EXPECT_LT(
        relative_error(relighter.relight(light, 2), relight_compressed_reference(field, light, 2)),
        float_tolerance)
        << terms << " terms";
    const std::vector<double> expected =
        cluster_light_products(field, light_in_field_basis(field, light));
    const std::vector<float> products = relighter.cluster_products(light);
    ASSERT_EQ(products.size(), expected.size());
    for (std::size_t i = 0; i < products.size(); ++i)
      ASSERT_NEAR(products[i], expected[i], 1e-5 * (1 + std::abs(expected[i])));
  }
}

TEST(OpenClRelighter, BatchedFramesMatchSingleFrames) {
  const CompressedField field = random_compressed_field(small_shape(40));
  OpenClRelighterOptions options;
  options.max_batch = 16;
  OpenClRelighter relighter(pocl(), field, options);
  // 3: frames padded to a vector of 4; 16: one full vector; 19: a pass of 16 and one of 3.
  for (const int frames : {3, 16, 19}) {
    std::vector<LightRgb> lights;
    for (int b = 0; b < frames; ++b)
      lights.push_back(random_light_vector(field.lights, 500 + std::uint64_t(frames * 100 + b)));
    const std::vector<Image> images = relighter.relight_batch(lights, 4);
    ASSERT_EQ(images.size(), lights.size());
    for (int b = 0; b < frames; ++b) {
      EXPECT_LT(relative_error(images[std::size_t(b)],
                               relight_compressed_reference(field, lights[std::size_t(b)], 4)),
                float_tolerance)
          << "frame " << b << " of " << frames;
      expect_unstored_zero(field, images[std::size_t(b)]);
    }
    EXPECT_EQ(relighter.last_timing().frames, frames);
  }
}

// Every layout relights the same: rows per work-item, slice height, and on CPUs the split of
// each row's entries between the slices (head) and row-vector groups (tail), for caps inside the
// head, across the split and past every row, in single frames and in a batch.
TEST(OpenClRelighter, EveryRowVectorWidthSliceAndHeadGivesTheSameImage) {
  const CompressedField field = random_compressed_field(small_shape(50));
  ASSERT_NE(field.stored_rows() % 32, 0u) << "the last slice should be partial";
  const std::vector<LightRgb> lights = {random_light_vector(field.lights, 51),
                                        random_light_vector(field.lights, 52),
                                        random_light_vector(field.lights, 53)};
  struct Layout {
    int row_vector, slice, head;
  };
  for (const Layout layout : std::vector<Layout>{{1, 32, 0},
                                                 {4, 16, 0},
                                                 {8, 8, 0},
                                                 {16, 4096, 0},
                                                 {1, 4096, 0},
                                                 {16, 4096, 3},
                                                 {16, 64, 1},
                                                 {4, 4096, 6}}) {
    OpenClRelighterOptions options;
    options.row_vector = layout.row_vector;
    options.slice_rows = layout.slice;
    options.head_entries = layout.head;
    options.work_group_rows = 64;
    OpenClRelighter relighter(pocl(), field, options);
    const std::string name = "row vector " + std::to_string(layout.row_vector) + ", slice " +
                             std::to_string(layout.slice) + ", head " + std::to_string(layout.head);
    for (const int cap : {2, 5, all_residual_entries}) {
      EXPECT_LT(relative_error(relighter.relight(lights[0], cap),
                               relight_compressed_reference(field, lights[0], cap)),
                float_tolerance)
          << name << ", cap " << cap;
      const std::vector<Image> batch = relighter.relight_batch(lights, cap);
      for (std::size_t b = 0; b < lights.size(); ++b)
        EXPECT_LT(relative_error(batch[b], relight_compressed_reference(field, lights[b], cap)),
                  float_tolerance)
            << name << ", cap " << cap << ", frame " << b;
    }
    if (layout.head > 0) {
      EXPECT_EQ(relighter.head_entries(), std::uint32_t(layout.head)) << name;
    }
  }
}

TEST(OpenClRelighter, GreyFieldsUseTheMeanOfTheRgbLight) {
  RandomFieldShape shape = small_shape(60);
  shape.channels = 1;
  const CompressedField field = random_compressed_field(shape);
  OpenClRelighter relighter(pocl(), field);
  const LightRgb light = random_light_vector(field.lights, 61);
  EXPECT_LT(relative_error(relighter.relight(light), relight_compressed_reference(field, light)),
            float_tolerance);
}

TEST(OpenClRelighter, HaarFieldsRelightLikeTheirIdentityOriginal) {
  // A field without residual whose bases are Haar-transformed relights, with the transformed
  // light vector, exactly like the original: the transform is orthonormal.
  RandomFieldShape shape = small_shape(70);
  shape.residual_per_function = 0;
  const CompressedField original = random_compressed_field(shape);
  CompressedField haar = original;
  haar.transform = BasisTransform::haar;
  for (int k = 0; k < haar.clusters; ++k)
    for (int j = 0; j < haar.terms; ++j)
      haar_forward(haar.bases.data() + (std::size_t(k) * haar.terms + j) * haar.lights, haar.lights,
                   1);
  const LightRgb light = random_light_vector(original.lights, 71);
  const Image expected = relight_compressed_reference(original, light);
  EXPECT_LT(relative_error(relight_compressed_reference(haar, light), expected), 1e-6);
  OpenClRelighter relighter(pocl(), haar);
  EXPECT_LT(relative_error(relighter.relight(light), expected), float_tolerance);
}

TEST(OpenClRelighter, FieldsWithoutStoredRowsOrBasisTerms) {
  RandomFieldShape shape = small_shape(80);
  shape.stored_fraction = 0;
  const CompressedField empty = random_compressed_field(shape);
  ASSERT_EQ(empty.stored_rows(), 0u);
  OpenClRelighter empty_relighter(pocl(), empty);
  for (const float value : empty_relighter.relight(random_light_vector(empty.lights, 81)).pixels)
    ASSERT_EQ(value, 0.0f);

  CompressedField residual_only = random_compressed_field(small_shape(82));
  residual_only.terms = 0;
  residual_only.weights.resize(residual_only.weights.rows(), 0);
  residual_only.bases.clear();
  OpenClRelighter relighter(pocl(), residual_only);
  const LightRgb light = random_light_vector(residual_only.lights, 83);
  EXPECT_LT(
      relative_error(relighter.relight(light), relight_compressed_reference(residual_only, light)),
      float_tolerance);
}

TEST(OpenClRelighter, ReportsKernelTimesAndCappedBytes) {
  RandomFieldShape shape = small_shape(90);
  shape.vary_residual = false;  // every stored row holds exactly 7 entries
  shape.stored_fraction = 1;
  const CompressedField field = random_compressed_field(shape);
  OpenClRelighter relighter(pocl(), field);
  const std::uint64_t rows = field.stored_rows();
  // 41 lights: one-byte light indices, so 5 bytes per entry read.
  EXPECT_EQ(relighter.residual_bytes(0), 0u);
  EXPECT_EQ(relighter.residual_bytes(3), rows * 3 * 5);
  EXPECT_EQ(relighter.residual_bytes(all_residual_entries), rows * 7 * 5);
  // Equal rows pad nothing but the unused rows of the last slice.
  const std::uint64_t slices = (rows + relighter.slice_rows() - 1) / relighter.slice_rows();
  const std::uint64_t slots = slices * relighter.slice_rows() * 7;
  EXPECT_DOUBLE_EQ(relighter.residual_padding(), double(slots - rows * 7) / double(slots));

  relighter.relight(random_light_vector(field.lights, 91), 3);
  const RelightTiming& timing = relighter.last_timing();
  ASSERT_EQ(timing.kernels.size(), 2u);
  EXPECT_EQ(timing.kernels[0].kernel, "gemv");
  EXPECT_EQ(timing.kernels[1].kernel, "rows");
  for (const auto& kernel : timing.kernels) EXPECT_GT(kernel.seconds, 0) << kernel.kernel;
  EXPECT_GE(timing.wall_seconds, timing.kernel_seconds());
  const std::uint64_t capped_rows_bytes = timing.kernel("rows").bytes;
  relighter.relight(random_light_vector(field.lights, 92), all_residual_entries);
  EXPECT_EQ(relighter.last_timing().kernel("rows").bytes - capped_rows_bytes, rows * 4 * 5);
}

// CPU slices are as tall as the padding allows: equal rows take 4096-row slices, and a field
// whose row lengths vary takes shorter ones, padding at most 1/8 of its entries. W lies in
// 16-row blocks inside them (each work-item's terms one contiguous run).
TEST(OpenClRelighter, CpuSlicesAreTallUnlessThePaddingGrows) {
  RandomFieldShape shape;  // 640 x 640 RGB, 12 entries per row
  const CompressedField equal = random_compressed_field(shape);
  EXPECT_EQ(tall_slice_rows(equal, 16, 24), 4096);
  OpenClRelighter relighter(pocl(), equal);
  EXPECT_EQ(relighter.slice_rows(), 4096);
  EXPECT_EQ(relighter.weight_rows(), 16);
  EXPECT_LE(relighter.residual_padding(), 1.0 / 9);

  shape.vary_residual = true;  // 0 to 12 entries per row, uniformly at random
  const CompressedField varied = random_compressed_field(shape);
  const int slice = tall_slice_rows(varied, 16, 24);
  EXPECT_LT(slice, 4096);
  EXPECT_GE(slice, 16);
  OpenClRelighter varied_relighter(pocl(), varied);
  EXPECT_EQ(varied_relighter.slice_rows(), slice);
  if (slice > 16) {
    EXPECT_LE(varied_relighter.residual_padding(), 1.0 / 9);
  }
  // An explicit slice height is kept; W's blocks are never taller than the slices.
  OpenClRelighterOptions options;
  options.slice_rows = 64;
  EXPECT_EQ(OpenClRelighter(pocl(), varied, options).slice_rows(), 64);
  options.slice_rows = 8;
  options.row_vector = 8;
  EXPECT_EQ(OpenClRelighter(pocl(), varied, options).weight_rows(), 8);
}

// The work ceiling (the row kernel with its reads kept in cache, writing nothing) takes time,
// counts the multiply-adds of the cap, and leaves the relighter relighting as before.
TEST(OpenClRelighter, WorkCeilingLeavesTheRelighterAsItWas) {
  const CompressedField field = random_compressed_field(small_shape(60));
  OpenClRelighter relighter(pocl(), field);
  const LightRgb light = random_light_vector(field.lights, 61);
  const Image before = relighter.relight(light, 3);
  EXPECT_EQ(relighter.last_timing().kernel("rows").flops,
            2 * field.stored_rows() * std::uint64_t(field.terms) +
                2 * relighter.residual_bytes(3) /
                    std::uint64_t(relighter.residual_value_bytes() + 1));  // 1-byte light ids
  for (const int frames : {1, 5, 40})  // 40: two passes of max_batch 32
    EXPECT_GT(relighter.work_ceiling_seconds(frames, 3), 0) << frames;
  EXPECT_EQ(relighter.relight(light, 3).pixels, before.pixels);
  EXPECT_LT(relative_error(relighter.relight_batch({light, light}, 3)[1],
                           relight_compressed_reference(field, light, 3)),
            float_tolerance);
}

TEST(OpenClRelighter, ReusedImagesAndBuffersStayCorrect) {
  const CompressedField field = random_compressed_field(small_shape(95));
  OpenClRelighter relighter(pocl(), field);
  std::vector<Image> images;
  for (int frame = 0; frame < 3; ++frame) {
    const LightRgb light = random_light_vector(field.lights, 96 + std::uint64_t(frame));
    relighter.relight_batch_into({light}, frame, images);
    ASSERT_EQ(images.size(), 1u);
    EXPECT_LT(relative_error(images[0], relight_compressed_reference(field, light, frame)),
              float_tolerance)
        << "frame " << frame;
    relighter.relight_residual_into(light, 2, images[0]);  // writes the same output buffer
    expect_unstored_zero(field, images[0]);
  }
}

TEST(OpenClRelighter, RefusesBadInput) {
  CompressedField field = random_compressed_field(small_shape(99));
  OpenClRelighter relighter(pocl(), field);
  EXPECT_THROW(relighter.relight(random_light_vector(field.lights, 1), -1), Error);
  EXPECT_THROW(relighter.relight(random_light_vector(field.lights - 1, 1)), Error);
  LightRgb light = random_light_vector(field.lights, 1);
  light(0, 0) = INFINITY;
  EXPECT_THROW(relighter.relight(light), Error);
  OpenClRelighterOptions options;
  options.row_vector = 3;
  EXPECT_THROW(OpenClRelighter(pocl(), field, options), Error);
  options.row_vector = 0;
  options.head_entries = -2;
  EXPECT_NE(testing::error_message([&] {
              OpenClRelighter(pocl(), field, options);
            }).find("head entries -2"),
            std::string::npos);
  field.residual.light_index[0] = std::uint32_t(field.lights);
  EXPECT_THROW(OpenClRelighter(pocl(), field), Error);
}

}  // namespace
}  // namespace relume
