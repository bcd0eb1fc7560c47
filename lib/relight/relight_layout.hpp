// The OpenCL relighter's device layout of a compressed field, built on the host before upload
// (kernels/relight.cl reads it), and the memory check of a relighting in it. Rows are padded to
// whole slices; W is slot-major inside blocks of weight_rows rows (a divisor of the slice rows:
// short on CPUs, so that a work-item's terms are one contiguous run and not one stream per term
// a slice apart). The residual has two regions, each a sequence
// of row groups stored slot-major (all of a group's rows' entry e, then entry e + 1) and padded to
// the group's longest row:
//   head: entries [0, head_entries) in groups of slice_rows rows (tall on CPUs, so that each
//         entry index of many rows is one contiguous run and a residual cap reads only its runs);
//   tail: entries from head_entries on, in groups of tail_rows rows (the row vector), where tall
//         groups would read too many runs at once. tail_rows 0: no tail (head_entries unlimited).
#pragma once

#include <cstddef>
#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// One residual region: group g's slots start at offsets[g] (offsets has one more entry: the end),
// width[g] entries per row, lanes[g] real rows.
struct ResidualRegion {
  int group_rows = 0;
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> width;
  std::vector<std::uint32_t> lanes;

  // Slots a cap reads: min(width, cap) entries of each real row, padding included.
  std::uint64_t slots_read(std::uint32_t cap) const;
};

struct RelightLayoutShape {
  int slice_rows = 32;
  int weight_rows = 0;                       // rows per block of W; 0: slice_rows
  int tail_rows = 0;                         // 0: every entry in the head
  std::uint32_t head_entries = 0xffffffffu;  // entries per row in the head
};

// W and the residual values as the kernels read them: float, or for a quantized field its
// integers (int8 when they fit, else int16) with the steps folded into the other factor: the
// blocks hold F^k x weight_step / residual_scale and the light vector is uploaded times
// residual_scale, so that W . (F I) and E . I come out in field units with no extra multiply.
struct StoredValues {
  int bytes = 4;                   // 4 (float), 2 (int16) or 1 (int8)
  std::vector<std::uint8_t> data;  // little-endian values of `bytes` bytes each

  const char* type() const { return bytes == 4 ? "float" : bytes == 2 ? "short" : "char"; }
};

struct RelightLayout {
  std::vector<std::uint32_t> stored_function;  // padded to whole slices
  std::vector<std::uint32_t> cluster;          // padded to whole slices
  StoredValues weights;                        // slot-major inside each block of weight_rows
  ResidualRegion head, tail;                   // the tail's slots follow the head's
  StoredValues residual_values;                // zero padded
  std::vector<std::uint32_t> residual_lights;
  std::vector<float> blocks;  // F^k in 2x2 blocks, zero-padded to even terms and lights
  float residual_scale = 1;   // the light vector's factor (the residual step, or 1)
};

RelightLayout lay_out_field(const CompressedField& field, const RelightLayoutShape& shape,
                            int lights_even);

// Refuses (Error with the numbers, core/memory_budget.hpp) a relighting whose field in this
// layout and `images` output images would not fit the memory budget. The OpenCL relighter checks
// one image before it lays the field out; a caller that holds more images at once checks those.
void check_relight_memory(const CompressedField& field, std::size_t images);

// Rows per slice for CPU devices: the tallest power of two from 4096 down to row_vector whose
// padding (each slice is as wide as its longest row's first head_entries entries, and the last
// slice's unused rows count too) adds at most 1/8 to those entries.
int tall_slice_rows(const CompressedField& field, int row_vector, std::uint32_t head_entries);

}  // namespace relume
