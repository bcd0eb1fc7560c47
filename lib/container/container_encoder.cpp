// Encoding a CompressedField into the container's sections (docs/container.md) and writing it.
#include <cmath>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/version.hpp>

#include "container/container.hpp"
#include "container/container_bit_set.hpp"
#include "container/container_bytes.hpp"
#include "container/container_encoding.hpp"
#include "container/container_format.hpp"
#include "container/container_sections.hpp"
#include "container/weight_prediction.hpp"
#include "core/atomic_file.hpp"
#include "model/cluster_terms.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/dark_gains.hpp"

namespace relume {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// `describe()` names the value for the error message; it is only called on failure.
template <class Describe>
std::uint16_t checked_half(float value, const Describe& describe, const std::string& where) {
  const std::uint16_t bits = float_to_half_bits(value);
  if (!std::isfinite(half_bits_to_float(bits)))
    throw Error(where + ": " + describe() + " is " + std::to_string(value) +
                ", beyond the largest half-precision value 65504: store it as float32");
  return bits;
}

// Writes values as f32, or as f16 after checking each fits.
template <class Describe>
std::string encode_values(const float* values, std::size_t count, ValuePrecision precision,
                          const Describe& describe, const std::string& where) {
  ByteWriter out;
  out.reserve(count * std::size_t(value_bytes(precision)));
  for (std::size_t i = 0; i < count; ++i) {
    if (precision == ValuePrecision::float16)
      out.u16(checked_half(
          values[i], [&] { return describe(i); }, where));
    else
      out.f32(values[i]);
  }
  return out.take();
}

json parse_parameters(const std::string& text, const std::string& where) {
  if (text.empty()) return json::object();
  json parameters;
  try {
    parameters = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(where + ": the compression parameters are not valid JSON: " + e.what());
  }
  if (!parameters.is_object())
    throw Error(where + ": the compression parameters must be a JSON object, got " +
                parameters.dump());
  return parameters;
}

}  // namespace

std::string encode_header(const CompressedField& shape, const StoredCounts& counts,
                          const ContainerOptions& options, const StoredWidths& widths,
                          const std::string& where) {
  return json{{"width", shape.width},
              {"height", shape.height},
              {"channels", shape.channels},
              {"lights", shape.lights},
              {"terms", shape.terms},
              {"clusters", shape.clusters},
              {"transform", shape.transform == BasisTransform::haar ? "haar" : "identity"},
              {"non_negative", shape.non_negative},
              {"stored_rows", counts.stored_rows},
              {"residual_nonzeros", counts.residual_nonzeros},
              {"weights_precision", to_string(stored_weight_precision(shape, options))},
              {"residual_precision", to_string(stored_residual_precision(shape, options))},
              {"weight_step", shape.quantization.weight_step},
              {"weight_coding", shape.coded_weights.empty() ? "values" : "jpeg2000_planes"},
              {"weight_planes_step", shape.coded_weights.empty() ? 0.0f : shape.coded_weights.step},
              {"residual_step", shape.quantization.residual_step},
              {"basis_bits", shape.quantization.basis_bits},
              {"dark_gain_step", shape.dark_gains.empty() ? 0.0f : shape.dark_gain_step},
              {"dark_gain_block", dark_gain_block},
              {"cluster_id_bits", 8 * widths.cluster_id_bytes},
              {"residual_length_bits", 8 * widths.residual_length_bytes},
              {"light_index_bits", 8 * widths.light_index_bytes},
              {"parameters", parse_parameters(options.parameters_json, where)},
              {"software", version_line()}}
      .dump();
}

FieldSections encode_field_sections(const CompressedField& field,
                                    const std::vector<std::uint64_t>& stored_functions) {
  FieldSections out;
  ByteWriter lights;
  for (const LightRgb* rows_of : {&field.directions, &field.intensities})
    for (Eigen::Index i = 0; i < field.lights; ++i)
      for (int c = 0; c < 3; ++c) lights.f32((*rows_of)(i, c));
  out.lights = lights.take();

  std::vector<std::uint64_t> inside;
  for (std::size_t q = 0; q < field.mask.size(); ++q)
    if (field.mask[q]) inside.push_back(q);
  out.mask = encode_bit_set(inside, field.mask.size());
  out.functions = encode_bit_set(stored_functions, std::uint64_t(field.functions()));
  out.dark_pixels =
      encode_bit_set(std::vector<std::uint64_t>(field.dark_pixels.begin(), field.dark_pixels.end()),
                     field.mask.size());

  ByteWriter dark;
  for (float v : field.dark) dark.f32(v);
  out.dark = dark.take();
  if (!field.dark_gains.empty()) {
    ByteWriter gains;
    for (const std::int32_t value : dark_gain_grid(field).values) gains.u16(std::uint16_t(value));
    out.dark_gains = gains.take();
  }

  const ValueQuantization& quantization = field.quantization;
  out.basis_bytes = basis_value_bytes(quantization.basis_bits);
  ByteWriter bases, basis_scales;
  for (float scale : quantization.basis_scales) basis_scales.f32(scale);
  for (std::size_t v = 0; v < field.bases.size(); ++v) {
    if (out.basis_bytes == 4) {
      bases.f32(field.bases[v]);
      continue;
    }
    const auto q =
        std::int32_t(std::lround(field.bases[v] / quantization.basis_scales[v / field.lights]));
    bases.unsigned_of_width(std::uint16_t(std::int16_t(q)), out.basis_bytes);
  }
  out.bases = bases.take();
  out.basis_scales = basis_scales.take();
  out.weight_planes.assign(field.coded_weights.codestream.begin(),
                           field.coded_weights.codestream.end());
  ByteWriter colour;
  for (const std::int16_t angle : field.coded_weights.colour_angles)
    colour.u16(std::uint16_t(angle));
  out.weight_colour = colour.take();
  return out;
}

RowSections encode_row_sections(const CompressedField& field, std::size_t first_row,
                                const ContainerOptions& options, const StoredWidths& widths,
                                const std::string& where) {
  RowSections out;
  const std::size_t rows = field.stored_rows() - first_row;
  ByteWriter clusters;
  clusters.reserve(rows * std::size_t(widths.cluster_id_bytes));
  for (std::size_t r = first_row; r < field.stored_rows(); ++r)
    clusters.unsigned_of_width(field.cluster[r], widths.cluster_id_bytes);
  out.clusters = clusters.take();

  const ResidualRows& e = field.residual;
  const std::size_t first_entry = e.row_offsets[first_row];
  ByteWriter lengths, indices;
  lengths.reserve(rows * std::size_t(widths.residual_length_bytes));
  indices.reserve((e.light_index.size() - first_entry) * std::size_t(widths.light_index_bytes));
  for (std::size_t r = first_row; r < field.stored_rows(); ++r)
    lengths.unsigned_of_width(e.length(r), widths.residual_length_bytes);
  for (std::size_t k = first_entry; k < e.light_index.size(); ++k)
    indices.unsigned_of_width(e.light_index[k], widths.light_index_bytes);
  out.lengths = lengths.take();
  out.indices = indices.take();

  const ValueQuantization& quantization = field.quantization;
  const ValuePrecision weight_precision = stored_weight_precision(field, options);
  const ValuePrecision residual_precision = stored_residual_precision(field, options);
  // A weight of an all-zero basis row adds nothing to the field and is not stored.
  const std::vector<std::uint8_t> stored_terms = used_basis_rows(field);
  auto is_stored = [&](std::size_t i) {
    return stored_terms[std::size_t(field.cluster[i / field.terms]) * field.terms +
                        i % field.terms] != 0;
  };
  const std::size_t first_weight = first_row * std::size_t(field.terms);
  if (!field.coded_weights.empty()) {
    // In the weight_planes section.
  } else if (weight_precision == ValuePrecision::quantized) {
    // Integers, stored as their camera-space prediction errors (the rows before first_row are
    // neighbours only).
    std::vector<std::int32_t> integers(std::size_t(field.weights.size()), 0);
    for (std::size_t i = 0; i < integers.size(); ++i)
      if (is_stored(i))
        integers[i] = std::int32_t(std::lround(field.weights.data()[i] / quantization.weight_step));
    std::size_t skipped = 0;
    for (std::size_t i = 0; i < first_weight; ++i) skipped += is_stored(i);
    const std::vector<std::uint16_t> errors = predict_weights(field, integers, stored_terms);
    integers = {};
    ByteWriter weights;
    weights.reserve((errors.size() - skipped) * 2);
    for (std::size_t k = skipped; k < errors.size(); ++k) weights.u16(errors[k]);
    out.weights = weights.take();
  } else {
    // W is row-major: stored rows x terms, each row's stored terms only.
    std::vector<float> values;
    std::vector<std::size_t> index_of;
    for (std::size_t i = first_weight; i < std::size_t(field.weights.size()); ++i)
      if (is_stored(i)) {
        values.push_back(field.weights.data()[i]);
        index_of.push_back(i);
      }
    out.weights = encode_values(
        values.data(), values.size(), weight_precision,
        [&](std::size_t v) { return weight_text(index_of[v], field.terms); }, where);
  }
  if (residual_precision == ValuePrecision::quantized) {
    ByteWriter values;
    values.reserve((e.values.size() - first_entry) * 2);
    for (std::size_t k = first_entry; k < e.values.size(); ++k)
      values.u16(
          std::uint16_t(std::int16_t(std::lround(e.values[k] / quantization.residual_step))));
    out.values = values.take();
  } else {
    out.values = encode_values(
        e.values.data() + first_entry, e.values.size() - first_entry, residual_precision,
        [&](std::size_t k) { return residual_entry_text(e, first_entry + k); }, where);
  }
  return out;
}

std::vector<StoredSection> sections_in_file_order(std::string header, FieldSections field,
                                                  RowSections rows, const StoredWidths& widths,
                                                  int weight_bytes, int residual_bytes) {
  std::vector<StoredSection> sections;
  sections.push_back({"header", std::move(header), 1});
  sections.push_back({"lights", std::move(field.lights), 4});
  sections.push_back({"mask", std::move(field.mask), 1});
  sections.push_back({"functions", std::move(field.functions), 1});
  sections.push_back({"dark_pixels", std::move(field.dark_pixels), 1});
  sections.push_back({"dark", std::move(field.dark), 4});
  sections.push_back({"dark_gains", std::move(field.dark_gains), 2});
  sections.push_back({"clusters", std::move(rows.clusters), widths.cluster_id_bytes});
  sections.push_back({"basis_scales", std::move(field.basis_scales), 4});
  sections.push_back({"bases", std::move(field.bases), field.basis_bytes});
  sections.push_back({"weights", std::move(rows.weights), weight_bytes});
  sections.push_back({"weight_planes", std::move(field.weight_planes), 1});
  sections.push_back({"weight_colour", std::move(field.weight_colour), 2});
  sections.push_back({"residual_offsets", std::move(rows.lengths), widths.residual_length_bytes});
  sections.push_back({"residual_indices", std::move(rows.indices), widths.light_index_bytes});
  sections.push_back({"residual_values", std::move(rows.values), residual_bytes});
  return sections;
}

StoredWidths resolved_widths(const CompressedField& shape, std::uint32_t longest_residual_row,
                             IndexWidth light_index, const std::string& where) {
  try {
    return {bytes_for_max_value(shape.clusters > 0 ? shape.clusters - 1 : 0),
            bytes_for_max_value(longest_residual_row),
            index_width_bits(resolve_light_index_width(light_index, shape.lights)) / 8};
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

namespace {

std::vector<StoredSection> encode_sections(const CompressedField& field,
                                           const ContainerOptions& options,
                                           const std::string& where) {
  validate_compressed_field(field, where);
  const StoredWidths widths =
      resolved_widths(field, field.residual.longest_row(), options.light_index, where);
  const StoredCounts counts{field.stored_rows(), field.residual.nonzeros()};
  return sections_in_file_order(
      encode_header(field, counts, options, widths, where),
      encode_field_sections(field, std::vector<std::uint64_t>(field.stored_function.begin(),
                                                              field.stored_function.end())),
      encode_row_sections(field, 0, options, widths, where), widths,
      value_bytes(stored_weight_precision(field, options)),
      value_bytes(stored_residual_precision(field, options)));
}

}  // namespace

std::string encode_container(const CompressedField& field, const ContainerOptions& options,
                             const std::string& where, ContainerLayout* layout) {
  return assemble_container(encode_sections(field, options, where), options.entropy_coding,
                            options.coding_threads, layout);
}

void write_container(const fs::path& path, const CompressedField& field,
                     const ContainerOptions& options) {
  write_file_atomically(path,
                        encode_container(field, options, "cannot write " + path.string(), nullptr));
}

ContainerLayout plan_container(const CompressedField& field, const ContainerOptions& options) {
  ContainerLayout layout;
  encode_container(field, options, "cannot store the compressed field", &layout);
  return layout;
}

CompressedField quantize_for_container(CompressedField field, const ContainerOptions& options) {
  const std::string where = "cannot store the compressed field";
  if (field.coded_weights.empty() &&
      stored_weight_precision(field, options) == ValuePrecision::float16)
    for (Eigen::Index i = 0; i < field.weights.size(); ++i) {
      float& w = field.weights.data()[i];
      w = half_bits_to_float(checked_half(
          w, [&] { return weight_text(std::size_t(i), field.terms); }, where));
    }
  if (stored_residual_precision(field, options) == ValuePrecision::float16)
    for (std::size_t k = 0; k < field.residual.values.size(); ++k) {
      float& v = field.residual.values[k];
      v = half_bits_to_float(checked_half(
          v, [&] { return residual_entry_text(field.residual, k); }, where));
    }
  return field;
}

RelativeError quantization_error(const CompressedField& field, const ContainerOptions& options) {
  return relative_error(field, quantize_for_container(field, options));
}

}  // namespace relume
