// What the container's encoder and decoder agree on about the sections' contents: the byte
// widths of ids, lengths and light indices, value sizes, and messages naming stored values.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <relume/container.hpp>
#include <string>

namespace relume {

struct StoredWidths {
  int cluster_id_bytes = 1;
  int residual_length_bytes = 1;
  int light_index_bytes = 1;
};

// Bytes of the smallest of u8 / u16 / u32 that holds values up to max_value.
int bytes_for_max_value(std::uint64_t max_value);

// 2 for float16 and quantized values (16-bit integers), 4 for float32.
int value_bytes(ValuePrecision precision);

// How the field's W and residual values are stored with `options`: quantized when the field's
// values are (ValueQuantization), else float16 when the options say so, else float32 (also when
// the options ask for quantized values the field does not have). Weights coded as planes count
// as float32 (their values in memory; the container holds the codestream).
ValuePrecision stored_weight_precision(const CompressedField& field,
                                       const ContainerOptions& options);
ValuePrecision stored_residual_precision(const CompressedField& field,
                                         const ContainerOptions& options);

// Bytes per stored basis value: 4 (float32), 1 (up to 8-bit integers) or 2 (up to 16).
int basis_value_bytes(int basis_bits);

// The product of sizes; throws Error("<where>: sizes overflow 64 bits").
std::uint64_t checked_product(std::initializer_list<std::uint64_t> factors,
                              const std::string& where);

// "the weight of stored row 3 term 1", "residual entry 2 of stored row 5": for messages.
std::string weight_text(std::size_t flat_index, int terms);
std::string residual_entry_text(const ResidualRows& residual, std::size_t k);

}  // namespace relume
