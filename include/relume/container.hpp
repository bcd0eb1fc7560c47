// relume/container.hpp: the .relume container, a CompressedField on disk, versioned and
// checksummed (byte layout in docs/container.md). A fixed preamble (magic "RELUME\0\0", format
// version, section table with one CRC-32 per section, CRC-32 of the table) is followed by the
// sections back to back: header (JSON), lights, mask, functions, dark pixels, clusters, bases,
// weights (or the weight planes, a JPEG 2000 codestream), residual_offsets, residual_indices,
// residual_values. Values are float32 by default; W and residual values may be stored as IEEE
// half or integers of a step, light indices as 8/16/32 bits. Every byte of the
// file is covered by a checksum and everything is validated on read: a truncated, altered or
// inconsistent file is refused with an Error naming the file and the section.
#pragma once

#include <cstdint>
#include <filesystem>
#include <relume/compressed_field.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace relume {

// The version write_container writes; read_container also reads versions 1 (no entropy coding)
// and 2 (every cluster stores a weight for each of its terms). From version 3 a stored row has
// no weight for a term whose basis row is all zero: the clusters that need fewer terms than the
// field's `terms` (model/cluster_terms.hpp) store only the weights they use. Version 4 adds
// the dark gains, version 5 the weights coded as JPEG 2000 planes (section 'weight_planes').
inline constexpr std::uint32_t container_format_version = 6;

// How W or the residual values are stored: float32, IEEE half, or integers times the field's
// quantization step (ValuePrecision::quantized: always so for a quantized field, see
// ValueQuantization in relume/compressed_field.hpp).
enum class ValuePrecision : std::uint8_t { float32, float16, quantized };
enum class IndexWidth : std::uint8_t { automatic, bits8, bits16, bits32 };

struct ContainerOptions {
  // For fields whose values are not quantized: float32 or float16 (a quantized part is always
  // stored as its integers; `quantized` here means float32 for a part that is not).
  ValuePrecision weights = ValuePrecision::float32;
  ValuePrecision residual = ValuePrecision::float32;  // residual values
  IndexWidth light_index = IndexWidth::automatic;     // residual light indices
  // zstd-compress every section after the filter that suits it (version 2); false stores the
  // sections' raw bytes (faster to write, larger, and easy to inspect).
  bool entropy_coding = true;
  // Threads that code the sections, several at once (0: one per core); the file is the same for
  // any count.
  unsigned coding_threads = 1;
  // Free-form compression parameters, a JSON object, recorded in the header. On read it comes
  // back re-serialised (same content, keys sorted).
  std::string parameters_json = "{}";
  // On read: the relume version and commit that wrote the file (version_line()); every write
  // records its own, whatever this holds. Empty for files written before it was recorded.
  std::string written_by;
};

struct ContainerSection {
  std::string name;
  std::uint64_t offset = 0;     // from the start of the file
  std::uint64_t bytes = 0;      // as stored in the file
  std::uint64_t raw_bytes = 0;  // after decoding (equal to bytes when stored raw)
  std::uint32_t crc32 = 0;      // of the stored bytes
  std::string coding = "raw";   // "raw", "zstd", "zstd+shuffle4", "zstd+delta2", ...
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
// inconsistent (lib/model/compressed_field_checks.hpp), the parameters are not a JSON object, a
// value does not fit the chosen precision (|x| > 65504 for half) or the lights do not fit the
// chosen index width.
void write_container(const std::filesystem::path& path, const CompressedField& field,
                     const ContainerOptions& options = {});

// Reads and validates a container. `stored_options`, when given, receives how it was stored:
// precisions, the light index width in use (never automatic) and the parameters.
CompressedField read_container(const std::filesystem::path& path,
                               ContainerOptions* stored_options = nullptr);

// The section table of a container, with every checksum verified (not the contents' meaning).
ContainerLayout describe_container(const std::filesystem::path& path);

}  // namespace relume
