// Consistency checks of a CompressedField in memory, part by part: the container writer runs all
// of them before writing, the reader runs each on the part it decoded from a section (so errors
// name the section), and reconstruction runs all of them before reading rows. Each throws
// Error("<where>: <what is wrong>, expected <what>").
#pragma once

#include <cstddef>
#include <cstdint>
#include <relume/compressed_field.hpp>
#include <string>

namespace relume {

// At most 2^32 functions: stored_function holds u32 function indices.
inline constexpr std::uint64_t max_compressed_functions = std::uint64_t(1) << 32;

// "stored row 12", for messages.
std::string stored_row_name(std::size_t row);

// width, height, channels, lights >= 1; terms, clusters >= 0; at most 2^32 functions; a known
// transform.
void check_dimensions(const CompressedField& field, const std::string& where);
// lights rows of directions and intensities, all finite; no direction of zero length.
void check_lights(const CompressedField& field, const std::string& where);
// width x height mask entries.
void check_mask(const CompressedField& field, const std::string& where);
// Stored functions strictly ascending and below width x height x channels.
void check_functions(const CompressedField& field, const std::string& where);
// One cluster id per stored row, each below clusters.
void check_clusters(const CompressedField& field, const std::string& where);
// clusters x terms x lights finite basis values.
void check_bases(const CompressedField& field, const std::string& where);
// W is stored rows x terms, finite; coded as planes, with a positive step (its values are not
// also quantized).
void check_weights(const CompressedField& field, const std::string& where);
// stored rows + 1 offsets from 0, non-decreasing, ending at the entry count; as many light
// indices as values. (No stored rows: empty offsets or {0} are both accepted.)
void check_residual_offsets(const CompressedField& field, const std::string& where);
// Light indices below lights, no light twice in a row. Needs valid offsets.
void check_residual_indices(const CompressedField& field, const std::string& where);
// Finite values, each row sorted by |value| descending. Needs valid offsets.
void check_residual_values(const CompressedField& field, const std::string& where);

// Dark pixels strictly ascending, below width x height, inside the mask and without stored rows.
// Needs valid functions and mask.
void check_dark_pixels(const CompressedField& field, const std::string& where);
// Channels x lights finite dark values when any pixel is dark (none otherwise). A container keeps
// them in a section of their own, which `where` names.
void check_dark_values(const CompressedField& field, const std::string& where);
// The dark gains: none, or one per dark pixel and channel, finite, >= 0, with a finite step > 0.
// (The container writer also needs them equal within each block: model/dark_gains.hpp.)
void check_dark_gains(const CompressedField& field, const std::string& where);
// All of the above, in that order; `context` prefixes the message (for example "cannot write
// scene.relume").
void validate_compressed_field(const CompressedField& field, const std::string& context);

}  // namespace relume
