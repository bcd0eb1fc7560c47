// Tests of compressed fields cut into strips of pixel rows and stacked back
// (model/compressed_field_rows.hpp): the round trip gives the field back member for member, with
// dark pixels, empty strips and quantization steps.
#include "model/compressed_field_rows.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>

#include "model/random_compressed_field.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

CompressedField field_with_dark_pixels() {
  RandomFieldShape shape;
  shape.width = 9;
  shape.height = 11;
  shape.lights = 12;
  shape.clusters = 5;
  shape.residual_per_function = 4;
  shape.vary_residual = true;
  shape.stored_fraction = 0.6;
  CompressedField field = random_compressed_field(shape);
  // Every other pixel none of whose functions is stored becomes a dark pixel (inside the mask).
  std::vector<bool> stored(std::size_t(field.width) * field.height, false);
  for (const std::uint32_t p : field.stored_function) stored[p / field.channels] = true;
  for (std::uint32_t q = 0; q < stored.size(); ++q)
    if (!stored[q] && q % 2 == 0) {
      field.dark_pixels.push_back(q);
      field.mask[q] = 1;
    }
  field.dark.assign(std::size_t(field.channels) * field.lights, 0.25f);
  field.quantization.weight_step = 0.5f;
  return field;
}

TEST(CompressedFieldRows, StripsStackBackIntoTheField) {
  const CompressedField field = field_with_dark_pixels();
  ASSERT_FALSE(field.dark_pixels.empty());
  for (const int strip_rows : {1, 4, 11}) {
    CompressedField stacked;
    for (int y = 0; y < field.height; y += strip_rows)
      append_compressed_rows(stacked,
                             compressed_rows(field, y, std::min(strip_rows, field.height - y)));
    EXPECT_EQ(stacked.height, field.height);
    EXPECT_EQ(stacked.mask, field.mask);
    EXPECT_EQ(stacked.stored_function, field.stored_function);
    EXPECT_EQ(stacked.cluster, field.cluster);
    EXPECT_TRUE(stacked.weights == field.weights);
    EXPECT_EQ(stacked.bases, field.bases);
    EXPECT_EQ(stacked.residual.row_offsets, field.residual.row_offsets);
    EXPECT_EQ(stacked.residual.light_index, field.residual.light_index);
    EXPECT_EQ(stacked.residual.values, field.residual.values);
    EXPECT_EQ(stacked.dark_pixels, field.dark_pixels);
    EXPECT_EQ(stacked.dark, field.dark);
    EXPECT_EQ(stacked.quantization.weight_step, field.quantization.weight_step);
  }
}

TEST(CompressedFieldRows, AStripReconstructsAsTheSameRowsOfTheWhole) {
  const CompressedField field = field_with_dark_pixels();
  const ReflectanceField whole = reconstruct_field(field);
  const CompressedField strip = compressed_rows(field, 3, 5);
  const ReflectanceField part = reconstruct_field(strip);
  const Eigen::Index row_functions = Eigen::Index(field.width) * field.channels;
  EXPECT_TRUE(part.values == whole.values.middleRows(3 * row_functions, 5 * row_functions));
  EXPECT_EQ(compressed_rows(field, 4, 0).stored_rows(), 0u);
  EXPECT_THROW(compressed_rows(field, 8, 4), Error);
  CompressedField other = strip;
  other.terms += 1;
  CompressedField stacked = strip;
  EXPECT_THROW(append_compressed_rows(stacked, other), Error);
}

}  // namespace
}  // namespace relume
