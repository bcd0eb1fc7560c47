// Tests of field folders written strip by strip: write_field_folder and the streaming
// reconstruction of a compressed field (`relume decompress`) give back, through load_field, the
// field and reconstruct_field's values exactly, with one strip or many, all lights open at once
// or a few per pass, and a residual cap; an interruption leaves no index behind.
#include "model/reconstructed_folder.hpp"

#include <relume/error.hpp>

#include "core/interruption.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::TempDir;

// 13x9 RGB, 7 lights, intensities that are powers of two (so that writing times them and
// loading divided by them is exact), part of the functions not stored, a partial mask.
CompressedField sample_field() {
  RandomFieldShape shape;
  shape.width = 13;
  shape.height = 9;
  shape.lights = 7;
  shape.clusters = 3;
  shape.terms = 2;
  shape.residual_per_function = 3;
  shape.vary_residual = true;
  shape.stored_fraction = 0.7;
  shape.seed = 21;
  CompressedField field = random_compressed_field(shape);
  for (int i = 0; i < field.lights; ++i) field.intensities.row(i).setConstant(float(1 << (i % 3)));
  return field;
}

void expect_same_values(const ReflectanceField& a, const ReflectanceField& b) {
  ASSERT_EQ(a.values.rows(), b.values.rows());
  ASSERT_EQ(a.values.cols(), b.values.cols());
  EXPECT_EQ((a.values - b.values).cwiseAbs().maxCoeff(), 0.0f);
  EXPECT_EQ(a.mask, b.mask);
  EXPECT_TRUE(a.intensities == b.intensities);
}

TEST(ReconstructedFolder, EqualsTheWholeReconstructionForAnyStripsAndPasses) {
  const CompressedField field = sample_field();
  const std::size_t row_bytes = std::size_t(field.width) * field.channels * sizeof(float);
  for (const StripLimits limits :
       {StripLimits{}, StripLimits{row_bytes, 2}, StripLimits{3 * row_bytes * 7, 3}}) {
    for (int cap : {all_residual_entries, 1}) {
      TempDir dir;
      write_reconstructed_folder(dir / "out", field, cap, limits);
      expect_same_values(load_field(dir / "out"), reconstruct_field(field, cap));
    }
  }
}

TEST(ReconstructedFolder, WriteFieldFolderRoundTripsThroughTheSameWriter) {
  const ReflectanceField field = reconstruct_field(sample_field());
  TempDir dir;
  write_field_folder(dir / "out", field);
  expect_same_values(load_field(dir / "out"), field);
}

TEST(ReconstructedFolder, AnInterruptionLeavesNoIndex) {
  TempDir dir;
  const CompressedField field = sample_field();
  const std::size_t row_bytes = std::size_t(field.width) * field.channels * sizeof(float);
  request_interruption();
  EXPECT_THROW(write_reconstructed_folder(dir / "out", field, all_residual_entries,
                                          StripLimits{row_bytes * 7, 0}),
               Interrupted);
  clear_interruption();
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "filenames.txt"));
  EXPECT_THROW(write_reconstructed_folder(dir / "bad", field, -2), Error);
  FieldFolderLayout four{1, 1, 4, LightDirections::Ones(2, 3), LightRgb::Ones(2, 3), {1}};
  EXPECT_THAT(testing::error_message([&] {
                write_field_folder_in_strips(dir / "four", four, [](int, int, int, int, float*) {});
              }),
              ::testing::HasSubstr("field folder of 4 channels"));
  EXPECT_FALSE(std::filesystem::exists(dir / "four"));
}

}  // namespace
}  // namespace relume
