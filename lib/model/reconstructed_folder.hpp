// `relume decompress`: a compressed field written back as a field folder (relume/field.hpp
// write_field_folder's layout) without the float32 field in memory: the pixels are reconstructed
// one strip of scanlines at a time (field/field_folder_writer.hpp), each stored row once per
// strip, and every light's image takes its rows of the strip.
#pragma once

#include <cstddef>
#include <filesystem>
#include <relume/compressed_field.hpp>

#include "field/field_folder_writer.hpp"

namespace relume {

// The memory the reconstruction needs besides the compressed field with the default limits: its
// strip of values and an index of the stored rows.
std::size_t reconstructed_folder_memory(const CompressedField& field);

// Throws Error for an inconsistent field or a negative cap, Error naming the file that cannot be
// written, Interrupted between strips when asked to stop.
void write_reconstructed_folder(const std::filesystem::path& folder, const CompressedField& field,
                                int residual_cap = all_residual_entries,
                                const StripLimits& limits = {});

}  // namespace relume
