// Implementation of the camera-space weight prediction.
#include "container/weight_prediction.hpp"

#include <algorithm>
#include <relume/error.hpp>

#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

// The stored rows of the left, above and above-left neighbours of each stored row (-1: none).
struct Neighbours {
  std::int64_t left = -1, up = -1, up_left = -1;
};

std::vector<Neighbours> neighbours(const CompressedField& field) {
  const std::vector<std::int64_t> row_of = stored_row_of_function(field);
  const std::int64_t row_stride = std::int64_t(field.width) * field.channels;
  std::vector<Neighbours> result(field.stored_rows());
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::int64_t p = field.stored_function[r];
    const std::int64_t x = (p / field.channels) % field.width, y = p / row_stride;
    if (x > 0) result[r].left = row_of[std::size_t(p - field.channels)];
    if (y > 0) result[r].up = row_of[std::size_t(p - row_stride)];
    if (x > 0 && y > 0) result[r].up_left = row_of[std::size_t(p - row_stride - field.channels)];
  }
  return result;
}

std::int32_t predict(const Neighbours& n, const std::vector<std::int32_t>& weights, int terms,
                     int j) {
  const auto at = [&](std::int64_t row) { return weights[std::size_t(row) * terms + j]; };
  if (n.left >= 0 && n.up >= 0) {
    const std::int32_t a = at(n.left), b = at(n.up);
    const std::int32_t c = n.up_left >= 0 ? at(n.up_left) : (a + b) / 2;
    if (c >= std::max(a, b)) return std::min(a, b);
    if (c <= std::min(a, b)) return std::max(a, b);
    return a + b - c;
  }
  if (n.left >= 0) return at(n.left);
  if (n.up >= 0) return at(n.up);
  return 0;
}

}  // namespace

std::uint64_t stored_weight_count(const CompressedField& field,
                                  const std::vector<std::uint8_t>& stored) {
  std::vector<std::uint64_t> per_cluster(field.clusters, 0);
  for (std::size_t row = 0; row < stored.size(); ++row)
    per_cluster[row / field.terms] += stored[row];
  std::uint64_t count = 0;
  for (std::uint32_t k : field.cluster) count += per_cluster[k];
  return count;
}

std::vector<std::uint16_t> predict_weights(const CompressedField& field,
                                           const std::vector<std::int32_t>& weights,
                                           const std::vector<std::uint8_t>& stored) {
  const std::vector<Neighbours> around = neighbours(field);
  std::vector<std::uint16_t> errors;
  errors.reserve(std::size_t(stored_weight_count(field, stored)));
  for (std::size_t r = 0; r < around.size(); ++r)
    for (int j = 0; j < field.terms; ++j) {
      if (!stored[std::size_t(field.cluster[r]) * field.terms + j]) continue;
      const std::size_t i = r * field.terms + j;
      errors.push_back(std::uint16_t(weights[i] - predict(around[r], weights, field.terms, j)));
    }
  return errors;
}

std::vector<std::int32_t> unpredict_weights(const CompressedField& field,
                                            const std::vector<std::uint16_t>& errors,
                                            const std::vector<std::uint8_t>& stored) {
  if (errors.size() != stored_weight_count(field, stored))
    throw Error("the weights hold " + std::to_string(errors.size()) +
                " prediction errors, the stored rows' clusters use " +
                std::to_string(stored_weight_count(field, stored)) + " terms");
  const std::vector<Neighbours> around = neighbours(field);
  std::vector<std::int32_t> weights(field.stored_rows() * std::size_t(field.terms), 0);
  std::size_t next = 0;
  // Neighbours come earlier in function order, so they are decoded before the row that uses them.
  for (std::size_t r = 0; r < around.size(); ++r)
    for (int j = 0; j < field.terms; ++j) {
      if (!stored[std::size_t(field.cluster[r]) * field.terms + j]) continue;
      const std::size_t i = r * field.terms + j;
      weights[i] =
          std::int16_t(std::uint16_t(errors[next++] + predict(around[r], weights, field.terms, j)));
    }
  return weights;
}

}  // namespace relume
