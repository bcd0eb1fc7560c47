// The parts of the container encoder (container_encoder.cpp) that a writer of a field held in
// strips (container_strips.hpp) shares with the whole-field one: the header, the sections of the
// field as a whole, the sections of its stored rows, and all of them in file order.
#pragma once

#include <cstdint>
#include <relume/container.hpp>
#include <string>
#include <vector>

#include "container/container_format.hpp"
#include "container/container_sections.hpp"

namespace relume {

struct StoredCounts {
  std::uint64_t stored_rows = 0;
  std::uint64_t residual_nonzeros = 0;
};

// The widths ids, residual lengths and light indices are stored with: `shape`'s clusters and
// lights (the light index width resolved from `light_index`) and its longest residual row.
// Throws Error("<where>: ...") when the lights do not fit the asked width.
StoredWidths resolved_widths(const CompressedField& shape, std::uint32_t longest_residual_row,
                             IndexWidth light_index, const std::string& where);

// The header section's JSON for a field of `shape` (its size, quantization and flags) holding
// `counts`.
std::string encode_header(const CompressedField& shape, const StoredCounts& counts,
                          const ContainerOptions& options, const StoredWidths& widths,
                          const std::string& where);

// Raw bytes of the sections that describe the field as a whole.
struct FieldSections {
  std::string lights, mask, functions, dark_pixels, dark, dark_gains, basis_scales, bases;
  std::string weight_planes;  // the codestream of W's planes, empty when W is stored as values
  std::string weight_colour;  // their colour transforms' angles (int16), empty without any
  int basis_bytes = 4;  // bytes per stored basis value
};

// `field`'s lights, mask, dark pixels and model, bases, coded weight planes; `stored_functions` (ascending function
// indices of the stored rows) make the functions section.
FieldSections encode_field_sections(const CompressedField& field,
                                    const std::vector<std::uint64_t>& stored_functions);

// Raw bytes of the sections with an entry per stored row.
struct RowSections {
  std::string clusters, weights, lengths, indices, values;
};

// The row sections of `field`'s stored rows from `first_row` on: a strip's, where the rows
// before `first_row` (the last pixel row of the strip above) are there only as the neighbours
// the quantized weights are predicted from (weight_prediction.hpp). Weights coded as planes are
// not in the row sections (FieldSections::weight_planes). Throws Error("<where>: ...")
// for a value that does not fit half precision when that is asked.
RowSections encode_row_sections(const CompressedField& field, std::size_t first_row,
                                const ContainerOptions& options, const StoredWidths& widths,
                                const std::string& where);

// The 16 sections of the current version in file order, with their numbers' sizes.
std::vector<StoredSection> sections_in_file_order(std::string header, FieldSections field,
                                                  RowSections rows, const StoredWidths& widths,
                                                  int weight_bytes, int residual_bytes);

}  // namespace relume
