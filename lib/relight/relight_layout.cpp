// Implementation of the relighter's device layout (see relight_layout.hpp).
#include "relight/relight_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <relume/error.hpp>
#include <string>

#include "core/memory_budget.hpp"

namespace relume {
namespace {

// The groups of one region over entries [first_entry, last_entry) of every row, its slots
// starting at `base`.
ResidualRegion plan_region(const CompressedField& field, int group_rows, std::uint32_t first_entry,
                           std::uint32_t last_entry, std::uint64_t base) {
  ResidualRegion region;
  region.group_rows = group_rows;
  const std::size_t rows = field.stored_rows();
  const std::size_t groups = (rows + group_rows - 1) / group_rows;
  region.offsets.assign(groups + 1, std::uint32_t(base));
  region.width.assign(groups, 0);
  region.lanes.assign(groups, 0);
  std::uint64_t end = base;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t end_row = std::min(rows, (g + 1) * group_rows);
    std::uint32_t width = 0;
    for (std::size_t s = g * group_rows; s < end_row; ++s) {
      const std::uint32_t length = std::min(field.residual.length(s), last_entry);
      width = std::max(width, length > first_entry ? length - first_entry : 0);
    }
    region.width[g] = width;
    region.lanes[g] = std::uint32_t(end_row - g * group_rows);
    end += std::uint64_t(width) * std::uint64_t(group_rows);
    if (end > 0xffffffffull)
      throw Error("OpenCL relighter: the padded residual holds more than 2^32 entries");
    region.offsets[g + 1] = std::uint32_t(end);
  }
  return region;
}

// `values` as the kernels store them: float when `step` is 0, else their integers (value / step,
// exact for a quantized field) in the narrowest of int8 and int16 that holds them all.
StoredValues store_values(const std::vector<float>& values, float step) {
  StoredValues stored;
  if (step <= 0) {
    stored.data.resize(values.size() * 4);
    if (!values.empty())  // memcpy of a null pointer is undefined even for 0 bytes
      std::memcpy(stored.data.data(), values.data(), stored.data.size());
    return stored;
  }
  std::vector<std::int32_t> integers(values.size());
  std::int32_t largest = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    integers[i] = std::int32_t(std::lround(values[i] / step));
    largest = std::max(largest, std::abs(integers[i]));
  }
  stored.bytes = largest <= 127 ? 1 : 2;
  stored.data.resize(values.size() * std::size_t(stored.bytes));
  for (std::size_t i = 0; i < values.size(); ++i)
    for (int b = 0; b < stored.bytes; ++b)
      stored.data[i * stored.bytes + b] = std::uint8_t(std::uint32_t(integers[i]) >> (8 * b));
  return stored;
}

// Copies the region's entries of every row into their slots.
void fill_region(const CompressedField& field, const ResidualRegion& region,
                 std::uint32_t first_entry, std::vector<float>& values,
                 std::vector<std::uint32_t>& lights) {
  const auto& residual = field.residual;
  const std::size_t group_rows = std::size_t(region.group_rows);
  for (std::size_t s = 0; s < field.stored_rows(); ++s) {
    const std::size_t g = s / group_rows;
    const std::uint32_t begin = residual.row_offsets[s];
    const std::uint32_t length = field.residual.length(s);
    for (std::uint32_t e = first_entry; e < std::min(length, first_entry + region.width[g]); ++e) {
      const std::size_t slot =
          region.offsets[g] + std::size_t(e - first_entry) * group_rows + s % group_rows;
      values[slot] = residual.values[begin + e];
      lights[slot] = residual.light_index[begin + e];
    }
  }
}

}  // namespace

std::uint64_t ResidualRegion::slots_read(std::uint32_t cap) const {
  std::uint64_t slots = 0;
  for (std::size_t g = 0; g < width.size(); ++g)
    slots += std::uint64_t(std::min(width[g], cap)) * lanes[g];
  return slots;
}

RelightLayout lay_out_field(const CompressedField& field, const RelightLayoutShape& shape,
                            int lights_even) {
  RelightLayout layout;
  const std::size_t rows = field.stored_rows();
  const std::size_t slice = std::size_t(shape.slice_rows);
  const std::size_t slices = (rows + slice - 1) / slice;
  const int terms = field.terms;
  layout.stored_function.assign(slices * slice, 0);
  layout.cluster.assign(slices * slice, 0);
  std::copy(field.stored_function.begin(), field.stored_function.end(),
            layout.stored_function.begin());
  std::copy(field.cluster.begin(), field.cluster.end(), layout.cluster.begin());
  const std::size_t block = shape.weight_rows > 0 ? std::size_t(shape.weight_rows) : slice;
  if (slice % block != 0)
    throw Error("relight layout: " + std::to_string(block) + " rows per block of W do not divide " +
                std::to_string(slice) + " rows per slice");
  std::vector<float> weights(slices * slice * terms, 0.0f);
  for (std::size_t s = 0; s < rows; ++s)
    for (int j = 0; j < terms; ++j)
      weights[(s / block * terms + j) * block + s % block] = field.weights(Eigen::Index(s), j);
  const ValueQuantization& quantization = field.quantization;
  layout.weights = store_values(weights, quantization.weight_step);

  const std::uint32_t head_entries = shape.tail_rows > 0 ? shape.head_entries : 0xffffffffu;
  layout.head = plan_region(field, shape.slice_rows, 0, head_entries, 0);
  // Without a tail every group of the tail region is empty.
  layout.tail = plan_region(field, shape.tail_rows > 0 ? shape.tail_rows : shape.slice_rows,
                            head_entries, 0xffffffffu, layout.head.offsets.back());
  std::vector<float> residual_values(layout.tail.offsets.back(), 0.0f);
  layout.residual_lights.assign(layout.tail.offsets.back(), 0);
  fill_region(field, layout.head, 0, residual_values, layout.residual_lights);
  if (shape.tail_rows > 0)
    fill_region(field, layout.tail, head_entries, residual_values, layout.residual_lights);
  layout.residual_values = store_values(residual_values, quantization.residual_step);
  layout.residual_scale = quantization.residual_step > 0 ? quantization.residual_step : 1.0f;
  const float block_scale =
      (quantization.weight_step > 0 ? quantization.weight_step : 1.0f) / layout.residual_scale;

  // Block (jb, ib) holds (F[2jb][2ib], F[2jb][2ib+1], F[2jb+1][2ib], F[2jb+1][2ib+1]).
  const int term_pairs = (terms + 1) / 2;
  const int light_pairs = lights_even / 2;
  layout.blocks.assign(std::size_t(field.clusters) * term_pairs * light_pairs * 4, 0.0f);
  for (int k = 0; k < field.clusters; ++k)
    for (int j = 0; j < terms; ++j)
      for (int i = 0; i < field.lights; ++i) {
        const std::size_t block = (std::size_t(k) * term_pairs + j / 2) * light_pairs + i / 2;
        layout.blocks[block * 4 + (j % 2) * 2 + i % 2] =
            field.basis(k)[std::size_t(j) * field.lights + i] * block_scale;
      }
  return layout;
}

void check_relight_memory(const CompressedField& field, std::size_t images) {
  // The relighter copies W, the bases and the residual into the kernels' layout (at most as large
  // as the decoded field), and relights into float RGB images of the field's size.
  const std::uint64_t model = std::uint64_t(field.weights.size()) * 4 + field.bases.size() * 4 +
                              field.residual.nonzeros() * 8 + field.stored_rows() * 12;
  const std::uint64_t image = std::uint64_t(field.width) * std::uint64_t(field.height) * 3 * 4;
  check_memory_need(model + images * image, "relighting " + std::to_string(field.width) + "x" +
                                                std::to_string(field.height) + " pixels (" +
                                                std::to_string(images) + " images at once)");
}

int tall_slice_rows(const CompressedField& field, int row_vector, std::uint32_t head_entries) {
  const std::size_t rows = field.stored_rows();
  std::uint64_t stored = 0;
  for (std::size_t s = 0; s < rows; ++s) stored += std::min(field.residual.length(s), head_entries);
  for (int slice = 4096; slice > row_vector; slice /= 2) {
    const ResidualRegion head = plan_region(field, slice, 0, head_entries, 0);
    if (std::uint64_t(head.offsets.back()) * 8 <= stored * 9) return slice;
  }
  return row_vector;
}

}  // namespace relume
