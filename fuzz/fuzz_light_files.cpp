// Fuzz target: every light-file parser on the same bytes: RTI .lp files, plain `x y z`
// direction rows and `R G B` rows (light intensities, light vectors), through the path-taking
// readers the commands use.
#include <cstddef>
#include <cstdint>

#include "field/light_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using relume::fuzz::expect_only_relume_errors;
  const auto lp = relume::fuzz::write_scratch_file("lights.lp", data, size);
  const auto rows = relume::fuzz::write_scratch_file("rows.txt", data, size);
  expect_only_relume_errors([&] { relume::read_lp_file(lp); });
  expect_only_relume_errors([&] { relume::read_light_directions(rows); });
  expect_only_relume_errors([&] { relume::read_rgb_rows(rows, "light intensity"); });
  return 0;
}
