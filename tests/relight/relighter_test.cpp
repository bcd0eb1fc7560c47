// The public relume::Relighter, on PoCL and with the CPU reference: all_residual_entries (the
// default cap) relights exactly as a cap of the field's longest residual row does, single and
// batched, and a negative cap is refused; and the memory check of a relighting
// (relight/relight_layout.hpp): what it counts, that it refuses with the numbers above the budget,
// and that the OpenCL relighter checks before it lays a field out.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <relume/error.hpp>
#include <relume/relight.hpp>

#include "core/memory_budget.hpp"
#include "model/random_compressed_field.hpp"
#include "relight/relight_layout.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;

CompressedField field_with_rows_of_every_length() {
  RandomFieldShape shape;
  shape.width = 20;
  shape.height = 12;
  shape.lights = 23;
  shape.clusters = 4;
  shape.terms = 3;
  shape.residual_per_function = 9;
  shape.vary_residual = true;  // rows of 0 to 9 entries: a cap of the longest cuts no row
  shape.seed = 17;
  return random_compressed_field(shape);
}

RelighterOptions pocl_or_reference(bool cpu_reference) {
  RelighterOptions options;
  options.cpu_reference = cpu_reference;
  if (!cpu_reference) options.device = "portable computing language";
  return options;
}

class RelighterResidualCap : public ::testing::TestWithParam<bool> {};  // CPU reference?

TEST_P(RelighterResidualCap, AllEntriesIsTheLongestRow) {
  const CompressedField field = field_with_rows_of_every_length();
  const int longest = int(field.residual.longest_row());
  ASSERT_EQ(longest, 9);
  Relighter relighter(field, pocl_or_reference(GetParam()));
  const LightRgb light = random_light_vector(field.lights, 3);
  const Image all = relighter.relight(light, all_residual_entries);
  EXPECT_EQ(all.pixels, relighter.relight(light, longest).pixels);
  EXPECT_EQ(all.pixels, relighter.relight(light).pixels);
  // A shorter cap leaves entries out: the comparison above is not vacuous.
  EXPECT_NE(all.pixels, relighter.relight(light, longest - 1).pixels);

  const std::vector<LightRgb> lights = {light, random_light_vector(field.lights, 4)};
  const std::vector<Image> batch = relighter.relight_batch(lights, all_residual_entries);
  const std::vector<Image> capped = relighter.relight_batch(lights, longest);
  ASSERT_EQ(batch.size(), 2u);
  for (std::size_t b = 0; b < batch.size(); ++b)
    EXPECT_EQ(batch[b].pixels, capped[b].pixels) << "frame " << b;
}

TEST_P(RelighterResidualCap, RefusesNegativeCaps) {
  const CompressedField field = field_with_rows_of_every_length();
  Relighter relighter(field, pocl_or_reference(GetParam()));
  const LightRgb light = random_light_vector(field.lights, 3);
  EXPECT_THROW(relighter.relight(light, -1), Error);
  EXPECT_THROW(relighter.relight_batch({light}, -1), Error);
}

INSTANTIATE_TEST_SUITE_P(Backends, RelighterResidualCap, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return std::string(info.param ? "cpu_reference" : "opencl");
                         });

// Sets a memory limit for one test and lifts it again.
class RelightMemory : public ::testing::Test {
 protected:
  void TearDown() override { set_memory_limit(0); }
};

TEST_F(RelightMemory, CountsTheLayoutAndEveryImage) {
  const CompressedField field = field_with_rows_of_every_length();
  // W and the bases as floats, a value and a light per residual entry, a function, a cluster and
  // an offset per stored row; and float RGB images of the field's size.
  const std::uint64_t model = field.weights.size() * 4 + field.bases.size() * 4 +
                              field.residual.nonzeros() * 8 + field.stored_rows() * 12;
  const std::uint64_t image = 20 * 12 * 3 * 4;
  set_memory_limit(model + 2 * image);
  EXPECT_NO_THROW(check_relight_memory(field, 2));
  const std::string message = testing::error_message([&] { check_relight_memory(field, 3); });
  EXPECT_THAT(message, HasSubstr("relighting 20x12 pixels (3 images at once) needs about"));
  EXPECT_THAT(message, HasSubstr("available (--memory-limit)"));
}

TEST_F(RelightMemory, TheOpenClRelighterChecksBeforeLayingTheFieldOut) {
  const CompressedField field = field_with_rows_of_every_length();
  set_memory_limit(1024);
  EXPECT_THAT(testing::error_message([&] { Relighter(field, pocl_or_reference(false)); }),
              HasSubstr("relighting 20x12 pixels (1 images at once) needs about"));
  // The CPU reference lays nothing out: it reads the field where it is.
  EXPECT_NO_THROW(Relighter(field, pocl_or_reference(true)));
}

}  // namespace
}  // namespace relume
