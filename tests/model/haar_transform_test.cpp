// Tests of the orthonormal Haar transform: hand-computed values (including the odd tail carried to
// the next level), inverse(forward(x)) == x, and preserved norms and dot products for any length
// and stride, which relighting in the Haar domain relies on.
#include "model/haar_transform.hpp"

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "support/test_support.hpp"

namespace relume {
namespace {

double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += double(a[i]) * b[i];
  return sum;
}

std::vector<float> random_values(int count, std::mt19937& random) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<float> values(count);
  for (float& v : values) v = normal(random);
  return values;
}

TEST(HaarTransform, HandComputedValues) {
  const float r = 1.0f / std::sqrt(2.0f);
  std::vector<float> two{3, 1};
  haar_forward(two.data(), 2, 1);
  EXPECT_FLOAT_EQ(two[0], 4 * r);
  EXPECT_FLOAT_EQ(two[1], 2 * r);

  // Constant of length 4: everything in the first coefficient, 2 * value.
  std::vector<float> four{5, 5, 5, 5};
  haar_forward(four.data(), 4, 1);
  EXPECT_FLOAT_EQ(four[0], 10);
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(four[i], 0, 1e-6);

  // Length 3: level 1 pairs (1, 2) and carries 3; level 2 pairs (3/sqrt2, 3).
  std::vector<float> three{1, 2, 3};
  haar_forward(three.data(), 3, 1);
  const float s1 = 3 * r;
  EXPECT_NEAR(three[0], (s1 + 3) * r, 1e-6);
  EXPECT_NEAR(three[1], (s1 - 3) * r, 1e-6);
  EXPECT_NEAR(three[2], -1 * r, 1e-6);

  // Length 1 is unchanged.
  float one = 7;
  haar_forward(&one, 1, 1);
  EXPECT_EQ(one, 7);
}

TEST(HaarTransform, InverseUndoesForwardAndPreservesNormAndDotProducts) {
  std::mt19937 random(1);
  std::vector<int> counts(40);
  std::iota(counts.begin(), counts.end(), 1);
  for (int extra : {63, 96, 97, 127, 240, 256, 1000}) counts.push_back(extra);
  for (const int count : counts) {
    const auto x = random_values(count, random);
    const auto y = random_values(count, random);
    auto hx = x, hy = y;
    haar_forward(hx.data(), count, 1);
    haar_forward(hy.data(), count, 1);
    const double scale = std::sqrt(dot(x, x) * dot(y, y));
    EXPECT_NEAR(dot(hx, hx), dot(x, x), 1e-5 * dot(x, x)) << "count " << count;
    EXPECT_NEAR(dot(hx, hy), dot(x, y), 1e-5 * scale) << "count " << count;
    auto back = hx;
    haar_inverse(back.data(), count, 1);
    for (int i = 0; i < count; ++i)
      EXPECT_NEAR(back[i], x[i], 1e-5f) << "count " << count << " at " << i;
  }
}

TEST(HaarTransform, BasisIsOrthonormal) {
  // Transforming each unit vector gives the columns of H; H^T H must be the identity.
  for (const int count : {5, 12, 96}) {
    std::vector<std::vector<float>> columns;
    for (int j = 0; j < count; ++j) {
      std::vector<float> e(count, 0.0f);
      e[j] = 1;
      haar_forward(e.data(), count, 1);
      columns.push_back(e);
    }
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < count; ++j)
        EXPECT_NEAR(dot(columns[i], columns[j]), i == j ? 1.0 : 0.0, 1e-6)
            << count << ": " << i << "," << j;
  }
}

TEST(HaarTransform, StrideTouchesOnlyItsOwnSequence) {
  std::mt19937 random(2);
  const int count = 97, stride = 3;
  const auto interleaved = random_values(count * stride, random);
  auto transformed = interleaved;
  haar_forward(transformed.data() + 1, count, stride);  // the middle channel only
  std::vector<float> alone(count);
  for (int i = 0; i < count; ++i) alone[i] = interleaved[i * stride + 1];
  haar_forward(alone.data(), count, 1);
  for (int i = 0; i < count; ++i) {
    EXPECT_EQ(transformed[i * stride + 0], interleaved[i * stride + 0]);
    EXPECT_EQ(transformed[i * stride + 1], alone[i]);
    EXPECT_EQ(transformed[i * stride + 2], interleaved[i * stride + 2]);
  }
  haar_inverse(transformed.data() + 1, count, stride);
  for (int i = 0; i < count * stride; ++i) EXPECT_NEAR(transformed[i], interleaved[i], 1e-5f);
}

}  // namespace
}  // namespace relume
