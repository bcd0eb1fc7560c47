// The container's names and shared helpers: precision and index-width names, the widths the
// sections are stored with, and the section lookup of a layout.
#include "container/container.hpp"

#include <algorithm>
#include <relume/error.hpp>

#include "container/container_sections.hpp"
#include "model/compressed_field_checks.hpp"

namespace relume {

int bytes_for_max_value(std::uint64_t max_value) {
  return max_value <= 0xFFu ? 1 : max_value <= 0xFFFFu ? 2 : 4;
}

int value_bytes(ValuePrecision precision) { return precision == ValuePrecision::float32 ? 4 : 2; }

namespace {

ValuePrecision stored_precision(float step, ValuePrecision asked) {
  if (step > 0) return ValuePrecision::quantized;
  return asked == ValuePrecision::float16 ? ValuePrecision::float16 : ValuePrecision::float32;
}

}  // namespace

ValuePrecision stored_weight_precision(const CompressedField& field,
                                       const ContainerOptions& options) {
  // Weights coded as planes are float32 values in memory; the header's precision says so.
  if (!field.coded_weights.empty()) return ValuePrecision::float32;
  return stored_precision(field.quantization.weight_step, options.weights);
}

ValuePrecision stored_residual_precision(const CompressedField& field,
                                         const ContainerOptions& options) {
  return stored_precision(field.quantization.residual_step, options.residual);
}

int basis_value_bytes(int basis_bits) { return basis_bits == 0 ? 4 : basis_bits <= 8 ? 1 : 2; }

std::uint64_t checked_product(std::initializer_list<std::uint64_t> factors,
                              const std::string& where) {
  std::uint64_t product = 1;
  for (std::uint64_t f : factors)
    if (__builtin_mul_overflow(product, f, &product))
      throw Error(where + ": sizes overflow 64 bits");
  return product;
}

std::string weight_text(std::size_t flat_index, int terms) {
  return "the weight of " + stored_row_name(flat_index / terms) + " term " +
         std::to_string(flat_index % terms);
}

std::string residual_entry_text(const ResidualRows& residual, std::size_t k) {
  const auto next = std::upper_bound(residual.row_offsets.begin(), residual.row_offsets.end(), k);
  const auto row = static_cast<std::size_t>(next - residual.row_offsets.begin()) - 1;
  return "residual entry " + std::to_string(k - residual.row_offsets[row]) + " of " +
         stored_row_name(row);
}

ValuePrecision parse_value_precision(const std::string& name) {
  if (name == "float32") return ValuePrecision::float32;
  if (name == "float16" || name == "half") return ValuePrecision::float16;
  if (name == "quantized") return ValuePrecision::quantized;
  throw Error("unknown precision \"" + name + "\": expected quantized, float32 or float16 (half)");
}

std::string to_string(ValuePrecision precision) {
  switch (precision) {
    case ValuePrecision::float16:
      return "float16";
    case ValuePrecision::quantized:
      return "quantized";
    case ValuePrecision::float32:
      break;
  }
  return "float32";
}

IndexWidth parse_index_width(const std::string& name) {
  if (name == "auto") return IndexWidth::automatic;
  if (name == "8") return IndexWidth::bits8;
  if (name == "16") return IndexWidth::bits16;
  if (name == "32") return IndexWidth::bits32;
  throw Error("unknown light index width \"" + name + "\": expected auto, 8, 16 or 32");
}

std::string to_string(IndexWidth width) {
  return width == IndexWidth::automatic ? "auto" : std::to_string(index_width_bits(width));
}

int index_width_bits(IndexWidth width) {
  switch (width) {
    case IndexWidth::bits8:
      return 8;
    case IndexWidth::bits16:
      return 16;
    case IndexWidth::bits32:
      return 32;
    case IndexWidth::automatic:
      break;
  }
  throw Error("the automatic light index width has no bit count until resolved for a light count");
}

IndexWidth resolve_light_index_width(IndexWidth requested, int lights) {
  if (requested == IndexWidth::automatic)
    return lights <= 256     ? IndexWidth::bits8
           : lights <= 65536 ? IndexWidth::bits16
                             : IndexWidth::bits32;
  const int bits = index_width_bits(requested);
  if (bits < 32 && std::int64_t(lights) > (std::int64_t(1) << bits))
    throw Error(std::to_string(bits) + "-bit light indices hold at most " +
                std::to_string(std::int64_t(1) << bits) + " lights, the field has " +
                std::to_string(lights) + ": use a wider index or auto");
  return requested;
}

const ContainerSection& ContainerLayout::section(std::string_view name) const {
  for (const ContainerSection& s : sections)
    if (s.name == name) return s;
  throw Error("the container has no section '" + std::string(name) + "'");
}

}  // namespace relume
