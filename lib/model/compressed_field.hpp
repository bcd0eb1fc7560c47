// A reflectance field compressed by clustered sparse residual factorization (paper Eq. 2):
//   R[p,:] ~ W[p,:] * F^{c(p)} + E[p,:]
// Only the functions that a scene needs are stored ("stored rows"): functions outside the mask and
// all-zero functions have no row and relight to zero. This is what the container file holds and
// what the relighting kernels read.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "field/reflectance_field.hpp"

namespace relume {

// Basis in which rows of F and the residual are expressed (paper Eq. 3). The relighter transforms
// the light vector the same way before use.
enum class BasisTransform : std::uint8_t { identity = 0, haar = 1 };

// Sparse residual rows in CSR form. Each row's entries are sorted by |value| descending, so every
// prefix of a row is the best residual of that length (the dynamic residual of paper section 4).
struct ResidualRows {
  std::vector<std::uint32_t> row_offsets;  // stored_rows + 1
  std::vector<std::uint32_t> light_index;  // nnz
  std::vector<float> values;               // nnz

  std::size_t rows() const { return row_offsets.empty() ? 0 : row_offsets.size() - 1; }
  std::size_t nonzeros() const { return values.size(); }
  std::uint32_t length(std::size_t row) const { return row_offsets[row + 1] - row_offsets[row]; }
  std::uint32_t longest_row() const {
    std::uint32_t longest = 0;
    for (std::size_t r = 0; r < rows(); ++r) longest = std::max(longest, length(r));
    return longest;
  }
};

struct CompressedField {
  int width = 0;
  int height = 0;
  int channels = 0;
  int lights = 0;    // m
  int terms = 0;     // t, basis functions per cluster
  int clusters = 0;  // K
  BasisTransform transform = BasisTransform::identity;
  std::vector<std::uint8_t> mask;  // width * height
  LightDirections directions;      // lights x 3
  LightRgb intensities;            // lights x 3

  std::vector<std::uint32_t> stored_function;  // stored row -> function index p, ascending
  std::vector<std::uint32_t> cluster;          // stored row -> cluster id in [0, clusters)
  RowMatrixF weights;                          // stored rows x terms (W)
  std::vector<float> bases;  // clusters * terms * lights: F^k[j][i] at (k * terms + j) * lights + i
  ResidualRows residual;     // stored rows, in the transformed basis

  std::size_t stored_rows() const { return stored_function.size(); }
  std::int64_t functions() const { return std::int64_t(width) * height * channels; }
  const float* basis(int k) const { return bases.data() + std::size_t(k) * terms * lights; }
};

}  // namespace relume
