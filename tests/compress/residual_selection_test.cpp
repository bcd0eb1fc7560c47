// Tests of residual selection: budgets parse, rows keep the largest entries above the threshold,
// sorted by |value| descending with their light index, so every prefix is the best shorter row;
// the allocation by peak spreads a field's entries by |value| / peak.
#include "compress/residual_selection.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>

#include "compress/peak_residual_allocation.hpp"

namespace relume {
namespace {

TEST(ResidualSelection, ParsesCountsAndPercentages) {
  EXPECT_EQ(ResidualBudget::parse("10").entries_for(96), 10);
  EXPECT_EQ(ResidualBudget::parse("500").entries_for(96), 96);
  EXPECT_EQ(ResidualBudget::parse("5%").entries_for(96), 5);  // 4.8 rounds to 5
  EXPECT_EQ(ResidualBudget::parse("100%").entries_for(96), 96);
  EXPECT_EQ(ResidualBudget::parse("0%").entries_for(96), 0);
  EXPECT_EQ(ResidualBudget::parse("2.5%").describe(), "2.5%");
  for (const char* bad : {"", "%", "-1", "abc", "5%%", "101%", "3.5", "1e3x"})
    EXPECT_THROW(ResidualBudget::parse(bad), Error) << bad;
}

TEST(ResidualSelection, KeepsTheLargestEntriesSortedByMagnitude) {
  RowMatrixF residual(2, 6);
  residual << 0.5f, -3.0f, 0.0f, 2.0f, -0.01f, 3.0f,  //
      0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f;
  const ResidualRows all = select_residual(residual, -1, 0.0f);
  ASSERT_EQ(all.rows(), 2u);
  EXPECT_EQ(all.row_offsets, (std::vector<std::uint32_t>{0, 5, 5}));
  // |3| ties: the lower light index first.
  EXPECT_EQ(all.light_index, (std::vector<std::uint32_t>{1, 5, 3, 0, 4}));
  EXPECT_EQ(all.values, (std::vector<float>{-3.0f, 3.0f, 2.0f, 0.5f, -0.01f}));

  const ResidualRows cut = select_residual(residual, 3, 0.0f);
  EXPECT_EQ(cut.row_offsets, (std::vector<std::uint32_t>{0, 3, 3}));
  EXPECT_EQ(cut.light_index, (std::vector<std::uint32_t>{1, 5, 3}));  // a prefix of `all`

  const ResidualRows thresholded = select_residual(residual, 10, 0.5f);
  EXPECT_EQ(thresholded.light_index, (std::vector<std::uint32_t>{1, 5, 3}));
}

TEST(ResidualSelection, RefusesNonFiniteResiduals) {
  RowMatrixF residual(1, 3);
  residual << 1.0f, std::numeric_limits<float>::infinity(), 0.0f;
  EXPECT_THROW(select_residual(residual, 2, 0.0f), Error);
}

TEST(ResidualSelection, ParsesAllocations) {
  EXPECT_EQ(parse_residual_allocation("per-function"), ResidualAllocation::per_function);
  EXPECT_EQ(parse_residual_allocation("peak"), ResidualAllocation::peak);
  EXPECT_STREQ(to_string(ResidualAllocation::peak), "peak");
  EXPECT_THROW(parse_residual_allocation("Peak"), Error);
}

TEST(PeakResidualAllocation, KeepsTheEntriesLargestRelativeToTheirFunctionsPeak) {
  // Row 0: peak 10, entries 3, 2, 1 (relative 0.3, 0.2, 0.1); row 1: peak 1, entries 0.5, -0.4,
  // 0.05 (relative 0.5, 0.4, 0.05). Three entries: both large ones of row 1, the first of row 0.
  ResidualRows rows;
  rows.row_offsets = {0, 3, 6};
  rows.light_index = {4, 0, 2, 1, 3, 0};
  rows.values = {3, 2, 1, 0.5f, -0.4f, 0.05f};
  const std::vector<double> peak = {10, 1};
  ResidualRows three = rows;
  keep_largest_relative_to_peak(three, peak, 3);
  EXPECT_EQ(three.row_offsets, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(three.light_index, (std::vector<std::uint32_t>{4, 1, 3}));
  EXPECT_EQ(three.values, (std::vector<float>{3, 0.5f, -0.4f}));
  ResidualRows five = rows;
  keep_largest_relative_to_peak(five, peak, 5);  // all but 0.05 of row 1
  EXPECT_EQ(five.row_offsets, (std::vector<std::uint32_t>{0, 3, 5}));
  ResidualRows all = rows;
  keep_largest_relative_to_peak(all, peak, 6);
  EXPECT_EQ(all.values, rows.values);
  ResidualRows none = rows;
  keep_largest_relative_to_peak(none, peak, 0);
  EXPECT_EQ(none.row_offsets, (std::vector<std::uint32_t>{0, 0, 0}));
  EXPECT_TRUE(none.values.empty());
}

}  // namespace
}  // namespace relume
