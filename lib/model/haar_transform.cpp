// Multi-level orthonormal Haar transform with the odd tail carried to the next level (see
// haar_transform.hpp). Each level goes through a per-thread scratch buffer.
#include "model/haar_transform.hpp"

#include <array>
#include <vector>

namespace relume {
namespace {

constexpr float inverse_sqrt2 = 0.70710678118654752440f;

std::vector<float>& scratch(int count) {
  thread_local std::vector<float> buffer;
  if (static_cast<int>(buffer.size()) < count) buffer.resize(count);
  return buffer;
}

}  // namespace

void haar_forward(float* values, int count, int stride) {
  if (count < 2) return;
  std::vector<float>& level = scratch(count);
  for (int n = count; n > 1; n = (n + 1) / 2) {
    const int pairs = n / 2;
    const int averages = (n + 1) / 2;
    for (int k = 0; k < pairs; ++k) {
      const float a = values[(2 * k) * stride];
      const float b = values[(2 * k + 1) * stride];
      level[k] = (a + b) * inverse_sqrt2;
      level[averages + k] = (a - b) * inverse_sqrt2;
    }
    if (n % 2 == 1) level[pairs] = values[(n - 1) * stride];
    for (int i = 0; i < n; ++i) values[i * stride] = level[i];
  }
}

void haar_inverse(float* values, int count, int stride) {
  if (count < 2) return;
  // The lengths of the forward levels, undone from the last (shortest) to the first.
  std::array<int, 32> lengths{};  // an int count halves to 1 in at most 31 levels
  int levels = 0;
  for (int n = count; n > 1; n = (n + 1) / 2) lengths[levels++] = n;
  std::vector<float>& level = scratch(count);
  while (levels > 0) {
    const int n = lengths[--levels];
    const int pairs = n / 2;
    const int averages = (n + 1) / 2;
    for (int k = 0; k < pairs; ++k) {
      const float s = values[k * stride];
      const float d = values[(averages + k) * stride];
      level[2 * k] = (s + d) * inverse_sqrt2;
      level[2 * k + 1] = (s - d) * inverse_sqrt2;
    }
    if (n % 2 == 1) level[n - 1] = values[pairs * stride];
    for (int i = 0; i < n; ++i) values[i * stride] = level[i];
  }
}

}  // namespace relume
