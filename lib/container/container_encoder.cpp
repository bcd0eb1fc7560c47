// Encoding a CompressedField into the container's sections (docs/container.md) and writing it.
#include <cmath>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/version.hpp>

#include "container/container.hpp"
#include "container/container_bit_set.hpp"
#include "container/container_bytes.hpp"
#include "container/container_format.hpp"
#include "container/container_sections.hpp"
#include "container/weight_prediction.hpp"
#include "core/atomic_file.hpp"
#include "model/cluster_terms.hpp"
#include "model/compressed_field_checks.hpp"

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

std::string encode_header(const CompressedField& field, const ContainerOptions& options,
                          const StoredWidths& widths, const std::string& where) {
  return json{{"width", field.width},
              {"height", field.height},
              {"channels", field.channels},
              {"lights", field.lights},
              {"terms", field.terms},
              {"clusters", field.clusters},
              {"transform", field.transform == BasisTransform::haar ? "haar" : "identity"},
              {"non_negative", field.non_negative},
              {"stored_rows", field.stored_rows()},
              {"residual_nonzeros", field.residual.nonzeros()},
              {"weights_precision", to_string(stored_weight_precision(field, options))},
              {"residual_precision", to_string(stored_residual_precision(field, options))},
              {"weight_step", field.quantization.weight_step},
              {"residual_step", field.quantization.residual_step},
              {"basis_bits", field.quantization.basis_bits},
              {"cluster_id_bits", 8 * widths.cluster_id_bytes},
              {"residual_length_bits", 8 * widths.residual_length_bytes},
              {"light_index_bits", 8 * widths.light_index_bytes},
              {"parameters", parse_parameters(options.parameters_json, where)},
              {"software", version_line()}}
      .dump();
}

std::vector<StoredSection> encode_sections(const CompressedField& field,
                                           const ContainerOptions& options,
                                           const std::string& where) {
  validate_compressed_field(field, where);
  IndexWidth light_index;
  try {
    light_index = resolve_light_index_width(options.light_index, field.lights);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  const StoredWidths widths = stored_widths(field, light_index);

  ByteWriter lights;
  for (const LightRgb* rows_of : {&field.directions, &field.intensities})
    for (Eigen::Index i = 0; i < field.lights; ++i)
      for (int c = 0; c < 3; ++c) lights.f32((*rows_of)(i, c));

  std::vector<std::uint64_t> inside;
  for (std::size_t q = 0; q < field.mask.size(); ++q)
    if (field.mask[q]) inside.push_back(q);

  ByteWriter dark;
  for (float v : field.dark) dark.f32(v);

  ByteWriter clusters;
  clusters.reserve(field.cluster.size() * std::size_t(widths.cluster_id_bytes));
  for (std::uint32_t k : field.cluster) clusters.unsigned_of_width(k, widths.cluster_id_bytes);

  const ValueQuantization& quantization = field.quantization;
  const int basis_bytes = basis_value_bytes(quantization.basis_bits);
  ByteWriter bases, basis_scales;
  for (float scale : quantization.basis_scales) basis_scales.f32(scale);
  for (std::size_t v = 0; v < field.bases.size(); ++v) {
    if (basis_bytes == 4) {
      bases.f32(field.bases[v]);
      continue;
    }
    const auto q =
        std::int32_t(std::lround(field.bases[v] / quantization.basis_scales[v / field.lights]));
    bases.unsigned_of_width(std::uint16_t(std::int16_t(q)), basis_bytes);
  }

  const ResidualRows& e = field.residual;
  ByteWriter lengths, indices;
  lengths.reserve(field.stored_rows() * std::size_t(widths.residual_length_bytes));
  indices.reserve(e.light_index.size() * std::size_t(widths.light_index_bytes));
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    lengths.unsigned_of_width(e.length(r), widths.residual_length_bytes);
  for (std::uint32_t light : e.light_index)
    indices.unsigned_of_width(light, widths.light_index_bytes);

  const ValuePrecision weight_precision = stored_weight_precision(field, options);
  const ValuePrecision residual_precision = stored_residual_precision(field, options);
  std::string weights, residual_values;
  // A weight of an all-zero basis row adds nothing to the field and is not stored.
  const std::vector<std::uint8_t> stored_terms = used_basis_rows(field);
  auto is_stored = [&](std::size_t i) {
    return stored_terms[std::size_t(field.cluster[i / field.terms]) * field.terms +
                        i % field.terms] != 0;
  };
  if (weight_precision == ValuePrecision::quantized) {
    // Integers, stored as their camera-space prediction errors.
    std::vector<std::int32_t> integers(std::size_t(field.weights.size()), 0);
    for (std::size_t i = 0; i < integers.size(); ++i)
      if (is_stored(i))
        integers[i] = std::int32_t(std::lround(field.weights.data()[i] / quantization.weight_step));
    const std::vector<std::uint16_t> errors = predict_weights(field, integers, stored_terms);
    integers = {};
    ByteWriter out;
    out.reserve(errors.size() * 2);
    for (std::uint16_t error : errors) out.u16(error);
    weights = out.take();
  } else {
    // W is row-major: stored rows x terms, each row's stored terms only.
    std::vector<float> values;
    std::vector<std::size_t> index_of;
    for (std::size_t i = 0; i < std::size_t(field.weights.size()); ++i)
      if (is_stored(i)) {
        values.push_back(field.weights.data()[i]);
        index_of.push_back(i);
      }
    weights = encode_values(
        values.data(), values.size(), weight_precision,
        [&](std::size_t v) { return weight_text(index_of[v], field.terms); }, where);
  }
  if (residual_precision == ValuePrecision::quantized) {
    ByteWriter out;
    out.reserve(e.values.size() * 2);
    for (float v : e.values)
      out.u16(std::uint16_t(std::int16_t(std::lround(v / quantization.residual_step))));
    residual_values = out.take();
  } else {
    residual_values = encode_values(
        e.values.data(), e.values.size(), residual_precision,
        [&](std::size_t k) { return residual_entry_text(e, k); }, where);
  }
  return {{"header", encode_header(field, options, widths, where), 1},
          {"lights", lights.take(), 4},
          {"mask", encode_bit_set(inside, field.mask.size()), 1},
          {"functions",
           encode_bit_set(std::vector<std::uint64_t>(field.stored_function.begin(),
                                                     field.stored_function.end()),
                          std::uint64_t(field.functions())),
           1},
          {"dark_pixels",
           encode_bit_set(
               std::vector<std::uint64_t>(field.dark_pixels.begin(), field.dark_pixels.end()),
               field.mask.size()),
           1},
          {"dark", dark.take(), 4},
          {"clusters", clusters.take(), widths.cluster_id_bytes},
          {"basis_scales", basis_scales.take(), 4},
          {"bases", bases.take(), basis_bytes},
          {"weights", std::move(weights), value_bytes(weight_precision)},
          {"residual_offsets", lengths.take(), widths.residual_length_bytes},
          {"residual_indices", indices.take(), widths.light_index_bytes},
          {"residual_values", std::move(residual_values), value_bytes(residual_precision)}};
}

}  // namespace

std::string encode_container(const CompressedField& field, const ContainerOptions& options,
                             const std::string& where, ContainerLayout* layout) {
  return assemble_container(encode_sections(field, options, where), options.entropy_coding, layout);
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
  if (stored_weight_precision(field, options) == ValuePrecision::float16)
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
