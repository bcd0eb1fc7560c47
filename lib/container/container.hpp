// The .relume container: a CompressedField on disk, versioned and checksummed (byte layout in
// docs/container.md). A fixed preamble (magic "RELUME\0\0", format version, section table with
// one CRC-32 per section, CRC-32 of the table) is followed by the sections back to back:
// header (JSON), lights, mask, functions, clusters, bases, weights, residual_offsets,
// residual_indices, residual_values. Values are float32 by default; W and residual values may be
// stored as IEEE half, light indices as 8/16/32 bits. Every byte of the file is covered by a
// checksum and everything is validated on read: a truncated, altered or inconsistent file is
// refused with an Error naming the file and the section.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "model/compressed_field.hpp"
#include "model/compressed_field_checks.hpp"  // validate_compressed_field
#include "model/reconstruct_field.hpp"

namespace relume {

inline constexpr std::uint32_t container_format_version = 1;

enum class ValuePrecision : std::uint8_t { float32, float16 };
enum class IndexWidth : std::uint8_t { automatic, bits8, bits16, bits32 };

// "float32" / "float16" (also "half"); throws Error naming the bad value.
ValuePrecision parse_value_precision(const std::string& name);
std::string to_string(ValuePrecision precision);
// "auto", "8", "16", "32"; throws Error naming the bad value.
IndexWidth parse_index_width(const std::string& name);
std::string to_string(IndexWidth width);
// 8, 16 or 32; throws Error for `automatic`, which has no width until resolved.
int index_width_bits(IndexWidth width);

// The smallest width that holds indices below `lights` (8 bits for <= 256 lights, 16 for
// <= 65536) when `requested` is automatic, else `requested` if it fits; throws Error if not.
IndexWidth resolve_light_index_width(IndexWidth requested, int lights);

struct ContainerOptions {
  ValuePrecision weights = ValuePrecision::float32;
  ValuePrecision residual = ValuePrecision::float32;  // residual values
  IndexWidth light_index = IndexWidth::automatic;     // residual light indices
  // Free-form compression parameters, a JSON object, recorded in the header. On read it comes
  // back re-serialised (same content, keys sorted).
  std::string parameters_json = "{}";
};

struct ContainerSection {
  std::string name;
  std::uint64_t offset = 0;  // from the start of the file
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;
};

struct ContainerLayout {
  std::uint32_t version = container_format_version;
  std::uint64_t preamble_bytes = 0;  // magic, version, section table and its checksum
  std::uint64_t file_bytes = 0;
  std::vector<ContainerSection> sections;  // in file order

  // Throws Error when there is no section of that name.
  const ContainerSection& section(std::string_view name) const;
};

// Writes atomically (temporary file, fsync, rename). Throws Error, writing nothing, if the field is
// inconsistent (validate_compressed_field), the parameters are not a JSON object, a value does not
// fit the chosen precision (|x| > 65504 for half) or the lights do not fit the chosen index width.
void write_container(const std::filesystem::path& path, const CompressedField& field,
                     const ContainerOptions& options = {});

// The layout write_container would produce (section sizes as really stored), without writing: it
// encodes the field in memory and keeps only the layout.
ContainerLayout plan_container(const CompressedField& field, const ContainerOptions& options = {});

// Reads and validates a container. `stored_options`, when given, receives how it was stored:
// precisions, the light index width in use (never automatic) and the parameters.
CompressedField read_container(const std::filesystem::path& path,
                               ContainerOptions* stored_options = nullptr);

// The section table of a container, with every checksum verified (not the contents' meaning).
ContainerLayout describe_container(const std::filesystem::path& path);

// The field as read_container would return it after write_container with `options`: W and
// residual values rounded through half where asked (everything else is stored exactly).
CompressedField quantize_for_container(const CompressedField& field,
                                       const ContainerOptions& options);

// The cost of the chosen precisions: relative_error (paper Eq. 16) of the quantised field against
// the unquantised one, over its stored rows, with the full residual. Exactly 0 when everything is
// float32.
RelativeError quantization_error(const CompressedField& field, const ContainerOptions& options);

}  // namespace relume
