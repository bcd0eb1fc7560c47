// Implementation of the residual allocation by peak (see peak_residual_allocation.hpp).
#include "compress/peak_residual_allocation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "compress/compression_target.hpp"

namespace relume {

void keep_largest_relative_to_peak(ResidualRows& residual, const std::vector<double>& peak,
                                   std::size_t total_entries) {
  if (total_entries >= residual.nonzeros()) return;
  std::vector<double> row_weight(peak.size());
  for (std::size_t r = 0; r < peak.size(); ++r)
    row_weight[r] = peak[r] > 0 ? 1.0 / (peak[r] * peak[r]) : 0.0;
  const std::vector<float> gains = residual_gains(residual, row_weight);  // (|value| / peak)^2
  float cut = HUGE_VALF;
  if (total_entries > 0) {
    std::vector<float> sorted = gains;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(total_entries - 1),
                     sorted.end(), std::greater<float>());
    cut = std::max(sorted[total_entries - 1], std::nextafter(0.0f, 1.0f));
  }
  keep_entries_with_gain(residual, gains, cut);
}

}  // namespace relume
