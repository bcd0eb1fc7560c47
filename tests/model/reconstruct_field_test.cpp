// Tests of field reconstruction (W F + capped residual, Haar inverse, unstored functions zero), the
// paper's Eq. 16 error with zero-energy functions left out, and `relume decompress` read back by
// load_field.
#include "model/reconstruct_field.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "container/container.hpp"
#include "model/haar_transform.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::TempDir;

// 6x5 pixels, 3 channels, 10 lights, 3 clusters, 2 terms, residual rows of 0 to 5 entries, about
// a third of the functions not stored.
CompressedField sample_field(std::uint64_t seed = 11) {
  RandomFieldShape shape;
  shape.width = 6;
  shape.height = 5;
  shape.channels = 3;
  shape.lights = 10;
  shape.clusters = 3;
  shape.terms = 2;
  shape.residual_per_function = 5;
  shape.vary_residual = true;
  shape.stored_fraction = 0.65;
  shape.seed = seed;
  return random_compressed_field(shape);
}

// Function p of the field written out term by term, in the stored basis.
std::vector<double> expected_stored_row(const CompressedField& field, std::size_t row, int cap) {
  std::vector<double> out(field.lights, 0.0);
  const int k = int(field.cluster[row]);
  for (int i = 0; i < field.lights; ++i)
    for (int j = 0; j < field.terms; ++j)
      out[i] += double(field.weights(Eigen::Index(row), j)) *
                field.bases[(std::size_t(k) * field.terms + j) * field.lights + i];
  const std::uint32_t begin = field.residual.row_offsets[row];
  const std::uint32_t end = field.residual.row_offsets[row + 1];
  for (std::uint32_t e = begin; e < end && e - begin < std::uint32_t(cap); ++e)
    out[field.residual.light_index[e]] += field.residual.values[e];
  return out;
}

TEST(ReconstructField, StoredRowsAreWFPlusResidualAndOthersAreZero) {
  const CompressedField field = sample_field();
  const ReflectanceField result = reconstruct_field(field);
  ASSERT_EQ(result.functions(), 90);
  ASSERT_EQ(result.lights(), 10);
  EXPECT_EQ(result.width, 6);
  EXPECT_EQ(result.height, 5);
  EXPECT_EQ(result.channels, 3);
  EXPECT_EQ(result.mask, field.mask);
  EXPECT_EQ(result.directions, field.directions);
  EXPECT_EQ(result.intensities, field.intensities);
  std::vector<bool> stored(90, false);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t p = field.stored_function[r];
    stored[p] = true;
    const std::vector<double> expected = expected_stored_row(field, r, all_residual_entries);
    for (int i = 0; i < 10; ++i)
      EXPECT_NEAR(result.values(p, i), expected[i], 1e-6) << "function " << p << " light " << i;
  }
  int unstored = 0;
  for (int p = 0; p < 90; ++p)
    if (!stored[p]) {
      ++unstored;
      EXPECT_EQ(result.values.row(p).norm(), 0.0f) << "function " << p;
    }
  EXPECT_GT(unstored, 10);
}

TEST(ReconstructField, ResidualCapKeepsTheLargestEntriesOfEachRow) {
  const CompressedField field = sample_field();
  std::size_t long_row = 0;
  while (field.residual.row_offsets[long_row + 1] - field.residual.row_offsets[long_row] < 3)
    ++long_row;
  const std::uint32_t p = field.stored_function[long_row];
  const std::uint32_t first = field.residual.row_offsets[long_row];
  const ReflectanceField none = reconstruct_field(field, 0);
  const ReflectanceField one = reconstruct_field(field, 1);
  // The longest row's length keeps every entry, as all_residual_entries (the default) does.
  const ReflectanceField all = reconstruct_field(field, int(field.residual.longest_row()));
  const std::vector<double> model = expected_stored_row(field, long_row, 0);
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(none.values(p, i), model[i], 1e-6);
  // Cap 1 differs from cap 0 only at the row's first (largest) entry's light, by its value.
  const std::uint32_t light = field.residual.light_index[first];
  for (int i = 0; i < 10; ++i)
    EXPECT_NEAR(one.values(p, i) - none.values(p, i),
                i == int(light) ? field.residual.values[first] : 0.0f, 1e-6);
  const ReflectanceField uncapped = reconstruct_field(field);
  EXPECT_EQ(all.values, uncapped.values);
  EXPECT_THROW(reconstruct_field(field, -1), Error);
}

TEST(ReconstructField, HaarStoredRowsAreTransformedBack) {
  CompressedField field = sample_field();
  field.transform = BasisTransform::haar;
  const ReflectanceField result = reconstruct_field(field);
  for (std::size_t r = 0; r < field.stored_rows(); r += 7) {
    const std::vector<double> stored = expected_stored_row(field, r, all_residual_entries);
    std::vector<float> expected(stored.begin(), stored.end());
    haar_inverse(expected.data(), 10, 1);
    for (int i = 0; i < 10; ++i)
      EXPECT_NEAR(result.values(field.stored_function[r], i), expected[i], 1e-5);
  }
  // reconstruct_stored_row stays in the stored (Haar) basis.
  std::vector<float> row(10);
  reconstruct_stored_row(field, 3, all_residual_entries, row.data());
  const std::vector<double> stored = expected_stored_row(field, 3, all_residual_entries);
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(row[i], stored[i], 1e-6);
}

TEST(RelativeError, IsZeroForTheExactFieldAndFollowsEquation16) {
  const CompressedField field = sample_field();
  ReflectanceField original = reconstruct_field(field);
  const RelativeError exact = relative_error(original, field, false);
  EXPECT_EQ(exact.mean, 0.0);

  // Zero energy: functions that are not stored are all-zero in `original` and are skipped.
  const std::int64_t unstored = 90 - std::int64_t(field.stored_rows());
  EXPECT_EQ(exact.zero_energy_skipped, unstored);
  EXPECT_EQ(exact.functions_averaged, std::int64_t(field.stored_rows()));

  // Change two functions: a stored one by a known amount, an unstored one (error 1: it
  // reconstructs as zero).
  const std::uint32_t p = field.stored_function[4];
  original.values(p, 2) += 0.5f;
  const double changed_energy = original.values.row(p).cast<double>().squaredNorm();
  std::uint32_t q = 0;
  while (std::find(field.stored_function.begin(), field.stored_function.end(), q) !=
         field.stored_function.end())
    ++q;
  original.values(q, 7) = 2.0f;
  const RelativeError error = relative_error(original, field, false, all_residual_entries, 2);
  EXPECT_EQ(error.functions_averaged, std::int64_t(field.stored_rows()) + 1);
  EXPECT_EQ(error.zero_energy_skipped, unstored - 1);
  const double expected = (0.25 / changed_energy + 1.0) / double(field.stored_rows() + 1);
  EXPECT_NEAR(error.mean, expected, 1e-6 * expected);
  // The same with one thread: the blocks add up in the same order.
  EXPECT_EQ(relative_error(original, field, false, all_residual_entries, 1).mean, error.mean);

  // Without the residual every stored row with a residual gets worse.
  EXPECT_GT(relative_error(original, field, false, 0).mean, error.mean);
}

TEST(RelativeError, MaskedOnlyAveragesInsideTheMask) {
  CompressedField field = sample_field();
  field.mask[0] = 0;  // pixel 0 (functions 0, 1, 2) leaves the mask
  ReflectanceField original = reconstruct_field(field);
  original.values(1, 0) += 1.0f;  // the only wrong function, outside the mask
  int pixel0_with_energy = 0;
  for (int p = 0; p < 3; ++p) pixel0_with_energy += original.values.row(p).squaredNorm() > 0;
  const double energy = original.values.row(1).cast<double>().squaredNorm();
  const RelativeError all = relative_error(original, field, false);
  const RelativeError masked = relative_error(original, field, true);
  EXPECT_EQ(all.functions_averaged, masked.functions_averaged + pixel0_with_energy);
  EXPECT_NEAR(all.mean * double(all.functions_averaged), 1.0 / energy, 1e-6 / energy);
  EXPECT_EQ(masked.mean, 0.0);
}

TEST(RelativeError, RefusesFieldsOfDifferentShapes) {
  const CompressedField field = sample_field();
  ReflectanceField original = reconstruct_field(field);
  original.values.conservativeResize(Eigen::NoChange, 9);
  EXPECT_THROW(relative_error(original, field, false), Error);
  EXPECT_THROW(relative_error(reconstruct_field(field), field, false, -3), Error);
}

TEST(RelativeError, BetweenTwoCompressionsOfTheSameField) {
  const CompressedField field = sample_field();
  EXPECT_EQ(relative_error(field, field).mean, 0.0);
  CompressedField no_residual = field;
  no_residual.residual.light_index.clear();
  no_residual.residual.values.clear();
  std::fill(no_residual.residual.row_offsets.begin(), no_residual.residual.row_offsets.end(), 0u);
  const RelativeError error = relative_error(field, no_residual);
  EXPECT_EQ(error.functions_averaged + error.zero_energy_skipped,
            std::int64_t(field.stored_rows()));
  EXPECT_NEAR(error.mean, relative_error(reconstruct_field(field), field, true, 0).mean, 1e-9);
}

TEST(DecompressCommand, WritesAFieldFolderThatLoadsBack) {
  TempDir dir;
  CompressedField field = sample_field();
  field.intensities.col(0).setConstant(2.0f);  // written multiplied back, loaded divided again
  write_container(dir / "a.relume", field);
  for (const int cap : {all_residual_entries, 1}) {
    const auto out = dir / ("field" + std::to_string(cap));
    const std::string residual =
        cap == all_residual_entries ? "" : " --residual " + std::to_string(cap);
    const auto run = testing::run_relume("decompress '" + (dir / "a.relume").string() + "' -o '" +
                                         out.string() + "'" + residual);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const ReflectanceField loaded = load_field(out);
    const ReflectanceField expected = reconstruct_field(field, cap);
    ASSERT_EQ(loaded.width, 6);
    ASSERT_EQ(loaded.height, 5);
    ASSERT_EQ(loaded.channels, 3);
    ASSERT_EQ(loaded.lights(), 10);
    EXPECT_LE((loaded.values - expected.values).cwiseAbs().maxCoeff(), 1e-6f);
    EXPECT_EQ(loaded.mask, expected.mask);
    EXPECT_LE((loaded.directions - field.directions).cwiseAbs().maxCoeff(), 1e-6f);
    EXPECT_LE((loaded.intensities - field.intensities).cwiseAbs().maxCoeff(), 1e-6f);
  }
  const auto refused = testing::run_relume("decompress '" + (dir / "a.relume").string() + "' -o '" +
                                           (dir / "x").string() + "' --residual -2");
  EXPECT_NE(refused.exit_code, 0);
  const auto missing = testing::run_relume("decompress '" + (dir / "none.relume").string() +
                                           "' -o '" + (dir / "y").string() + "'");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("container not found"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace relume
