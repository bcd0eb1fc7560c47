// Implementation of residual selection (see residual_selection.hpp).
#include "compress/residual_selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <relume/error.hpp>

namespace relume {

ResidualAllocation parse_residual_allocation(const std::string& text) {
  if (text == "per-function") return ResidualAllocation::per_function;
  if (text == "peak") return ResidualAllocation::peak;
  throw Error("residual allocation '" + text + "' is invalid: expected per-function or peak");
}

const char* to_string(ResidualAllocation allocation) {
  return allocation == ResidualAllocation::peak ? "peak" : "per-function";
}

void append_residual_row(const float* residual, int lights, int max_entries, float threshold,
                         ResidualRows& rows, std::vector<int>& scratch) {
  scratch.clear();
  for (int i = 0; i < lights; ++i) {
    if (!std::isfinite(residual[i]))
      throw Error("residual of light " + std::to_string(i) + " is not finite (" +
                  std::to_string(residual[i]) + ")");
    if (residual[i] != 0.0f && std::fabs(residual[i]) > threshold) scratch.push_back(i);
  }
  const auto larger = [&](int a, int b) {
    const float fa = std::fabs(residual[a]), fb = std::fabs(residual[b]);
    return fa != fb ? fa > fb : a < b;
  };
  std::size_t kept = scratch.size();
  if (max_entries >= 0 && kept > std::size_t(max_entries)) {
    kept = std::size_t(max_entries);
    std::partial_sort(scratch.begin(), scratch.begin() + kept, scratch.end(), larger);
  } else {
    std::sort(scratch.begin(), scratch.end(), larger);
  }
  for (std::size_t k = 0; k < kept; ++k) {
    rows.light_index.push_back(static_cast<std::uint32_t>(scratch[k]));
    rows.values.push_back(residual[scratch[k]]);
  }
  rows.row_offsets.push_back(static_cast<std::uint32_t>(rows.values.size()));
}

ResidualRows select_residual(const RowMatrixF& residual, int max_entries, float threshold) {
  ResidualRows rows;
  rows.row_offsets.reserve(residual.rows() + 1);
  rows.row_offsets.push_back(0);
  std::vector<int> scratch;
  for (Eigen::Index r = 0; r < residual.rows(); ++r)
    append_residual_row(residual.row(r).data(), static_cast<int>(residual.cols()), max_entries,
                        threshold, rows, scratch);
  return rows;
}

}  // namespace relume
