// Tests of the whole-array value checks (core/value_scans.hpp): a single NaN, infinity or
// negative value anywhere in a large array, first, last or in the middle, is found; the extremes
// that are allowed (the largest float, denormals, negative zero) pass.
#include "core/value_scans.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace relume {
namespace {

using Limits = std::numeric_limits<float>;

TEST(ValueScans, OneNonFiniteValueAnywhereIsFound) {
  std::vector<float> values(100003, 0.5f);
  EXPECT_TRUE(all_finite(values.data(), values.size()));
  EXPECT_TRUE(all_finite(values.data(), 0));
  for (const float bad : {Limits::quiet_NaN(), Limits::infinity(), -Limits::infinity()})
    for (const std::size_t at : {std::size_t(0), values.size() / 2, values.size() - 1}) {
      std::vector<float> with = values;
      with[at] = bad;
      EXPECT_FALSE(all_finite(with.data(), with.size())) << bad << " at " << at;
    }
  values.front() = Limits::max();
  values[7] = -Limits::max();
  values.back() = Limits::denorm_min();
  EXPECT_TRUE(all_finite(values.data(), values.size()));
}

TEST(ValueScans, OneNegativeValueAnywhereIsFound) {
  std::vector<float> values(100003, 0.0f);
  values[3] = -0.0f;  // not below zero
  values[5] = Limits::max();
  values[9] = Limits::quiet_NaN();  // not below zero either: all_finite refuses it
  EXPECT_TRUE(all_non_negative(values.data(), values.size()));
  for (const float bad : {-Limits::denorm_min(), -1.0f, -Limits::infinity()})
    for (const std::size_t at : {std::size_t(0), values.size() / 2, values.size() - 1}) {
      std::vector<float> with = values;
      with[at] = bad;
      EXPECT_FALSE(all_non_negative(with.data(), with.size())) << bad << " at " << at;
    }
}

}  // namespace
}  // namespace relume
