// Container internals behind relume/container.hpp: parsing of the precision and index-width
// names, the layout a field would have without writing it, and the rounding that storage applies.
#pragma once

#include <cstdint>
#include <filesystem>
#include <relume/container.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "model/compressed_field_checks.hpp"  // validate_compressed_field
#include "model/reconstruct_field.hpp"

namespace relume {

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

// read_container of a file's bytes already in memory; `path` names it in errors (the fuzz
// targets decode their inputs this way).
CompressedField decode_container(const std::string& bytes, const std::filesystem::path& path,
                                 ContainerOptions* stored_options = nullptr);

// The bytes write_container writes for `field`, in memory; errors begin with `where`, and
// `layout`, when given, receives the layout.
std::string encode_container(const CompressedField& field, const ContainerOptions& options,
                             const std::string& where, ContainerLayout* layout);

// The layout write_container would produce (section sizes as really stored), without writing: it
// encodes the field in memory and keeps only the layout.
ContainerLayout plan_container(const CompressedField& field, const ContainerOptions& options = {});

// The field as read_container would return it after write_container with `options`: W and
// residual values rounded through half where asked (everything else is stored exactly).
// (By value: pass it with std::move to round it without a copy.)
CompressedField quantize_for_container(CompressedField field, const ContainerOptions& options);

// The cost of the chosen precisions: relative_error (paper Eq. 16) of the quantised field against
// the unquantised one, over its stored rows, with the full residual. Exactly 0 when everything is
// float32.
RelativeError quantization_error(const CompressedField& field, const ContainerOptions& options);

}  // namespace relume
