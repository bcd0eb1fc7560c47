// Tests of how work is shared over ranks (core/ranks.hpp): weighted_shares cuts consecutive items
// (pixel rows weighted by their stored functions) into shares of nearly equal weight.
#include "core/ranks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace relume {
namespace {

// The weight of every share that `boundaries` cut from `weights`.
std::vector<std::uint64_t> share_weights(const std::vector<std::uint64_t>& weights,
                                         const std::vector<int>& boundaries) {
  std::vector<std::uint64_t> shares;
  for (std::size_t r = 0; r + 1 < boundaries.size(); ++r)
    shares.push_back(std::accumulate(weights.begin() + boundaries[r],
                                     weights.begin() + boundaries[r + 1], std::uint64_t(0)));
  return shares;
}

TEST(WeightedShares, EveryShareIsWithinTheHeaviestItemOfAnEvenSplit) {
  // Rows of a frame whose top third is dark: evenly by rows, the first of two ranks would get a
  // third of the weight.
  std::vector<std::uint64_t> weights(300, 0);
  for (std::size_t y = 100; y < 300; ++y) weights[y] = 90 + y % 7;
  for (const int parts : {1, 2, 3, 5, 8}) {
    const std::vector<int> boundaries = weighted_shares(weights, parts);
    ASSERT_EQ(boundaries.size(), std::size_t(parts) + 1);
    EXPECT_EQ(boundaries.front(), 0);
    EXPECT_EQ(boundaries.back(), 300);
    EXPECT_TRUE(std::is_sorted(boundaries.begin(), boundaries.end()));
    const double even =
        double(std::accumulate(weights.begin(), weights.end(), std::uint64_t(0))) / parts;
    for (const std::uint64_t share : share_weights(weights, boundaries))
      EXPECT_LE(std::abs(double(share) - even), 96.0) << parts << " parts";
  }
  // Two parts: the dark rows all go to the first, which ends well past row 150.
  EXPECT_EQ(weighted_shares(weights, 2)[1], 200);
}

TEST(WeightedShares, NoWeightSplitsByCount) {
  EXPECT_EQ(weighted_shares(std::vector<std::uint64_t>(10, 0), 3), (std::vector<int>{0, 3, 6, 10}));
  EXPECT_EQ(weighted_shares({}, 2), (std::vector<int>{0, 0, 0}));
}

TEST(WeightedShares, OneHeavyItemLeavesOtherSharesEmptyRatherThanSplittingIt) {
  const std::vector<int> boundaries = weighted_shares({0, 0, 1000, 0, 0}, 3);
  ASSERT_EQ(boundaries.size(), 4u);
  EXPECT_TRUE(std::is_sorted(boundaries.begin(), boundaries.end()));
  const std::vector<std::uint64_t> shares = share_weights({0, 0, 1000, 0, 0}, boundaries);
  EXPECT_EQ(std::count(shares.begin(), shares.end(), 1000u), 1);
  // More parts than items: some shares are empty, none overlap.
  const std::vector<int> many = weighted_shares({5, 5}, 4);
  EXPECT_EQ(many.front(), 0);
  EXPECT_EQ(many.back(), 2);
  EXPECT_TRUE(std::is_sorted(many.begin(), many.end()));
  EXPECT_EQ(share_weights({5, 5}, many), (std::vector<std::uint64_t>{0, 5, 0, 5}));
}

}  // namespace
}  // namespace relume
