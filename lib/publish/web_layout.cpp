// Implementation of the web layout of a compressed field (web_layout.hpp).
#include "publish/web_layout.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <relume/error.hpp>

#include "container/weight_prediction.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/quantization.hpp"
#include "model/reconstruct_field.hpp"
#include "publish/field_region.hpp"
#include "publish/web_bundle.hpp"

namespace relume {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the web layout writes the host's bytes as little-endian arrays");

template <typename T>
std::string raw_bytes(const std::vector<T>& values) {
  std::string bytes(values.size() * sizeof(T), '\0');
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

// The narrowest of uint8, uint16, uint32 for values below `limit`.
std::string id_type(std::uint64_t limit) {
  return limit <= 256 ? "uint8" : limit <= 65536 ? "uint16" : "uint32";
}

BundleArray id_array(const std::string& name, const std::string& type,
                     const std::vector<std::uint32_t>& ids) {
  if (type == "uint8")
    return {name, type, raw_bytes(std::vector<std::uint8_t>(ids.begin(), ids.end()))};
  if (type == "uint16")
    return {name, type, raw_bytes(std::vector<std::uint16_t>(ids.begin(), ids.end()))};
  return {name, type, raw_bytes(ids)};
}

BundleArray bit_set(const std::string& name, const std::vector<std::uint32_t>& members,
                    std::uint64_t size) {
  std::vector<std::uint8_t> bits((size + 7) / 8, 0);
  for (std::uint32_t i : members) bits[i / 8] |= std::uint8_t(1u << (i % 8));
  return {name, "uint8", raw_bytes(bits)};
}

// Whether every value is exactly float(q) * step for an integer |q| <= max_quantized_value (how
// a quantized field holds them).
bool multiples_of(const float* values, std::size_t count, float step) {
  if (!(step > 0)) return false;
  for (std::size_t i = 0; i < count; ++i) {
    const double q = std::round(double(values[i]) / step);
    if (std::abs(q) > max_quantized_value || float(float(q) * step) != values[i]) return false;
  }
  return true;
}

std::vector<std::int32_t> integers(const float* values, std::size_t count, float step) {
  std::vector<std::int32_t> result(count);
  for (std::size_t i = 0; i < count; ++i) result[i] = std::int32_t(std::lround(values[i] / step));
  return result;
}

// The integers of values stored as rows of `row_length` values with one step per row.
std::vector<std::int32_t> integers_per_row(const std::vector<float>& values,
                                           const std::vector<float>& steps, int row_length) {
  std::vector<std::int32_t> result(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    result[i] = std::int32_t(std::lround(values[i] / steps[i / std::size_t(row_length)]));
  return result;
}

// What every tile stores, decided once for the field so that all tiles share the manifest's
// types.
struct TileTypes {
  bool weights = true;  // false: the page takes them from data/weights.j2k
  bool quantized_weights = false, quantized_residual = false, dark = false, gains = false;
  std::string cluster_type, length_type, light_type;
};

std::vector<BundleArray> tile_arrays(const CompressedField& part, const TileTypes& types) {
  std::vector<BundleArray> arrays;
  arrays.push_back(
      bit_set("stored_functions", part.stored_function, std::uint64_t(part.functions())));
  arrays.push_back(id_array("clusters", types.cluster_type, part.cluster));
  const std::size_t weight_count = std::size_t(part.weights.size());
  if (types.quantized_weights) {
    // Every term counts as stored: unused terms hold zeros, which predict and code to nearly
    // nothing, and the page needs no per-cluster term table.
    const std::vector<std::uint8_t> all_terms(std::size_t(part.clusters) * part.terms, 1);
    arrays.push_back(
        {"weights", "med16",
         raw_bytes(predict_weights(
             part, integers(part.weights.data(), weight_count, part.quantization.weight_step),
             all_terms))});
  } else if (types.weights) {
    arrays.push_back(
        {"weights", "float32",
         raw_bytes(std::vector<float>(part.weights.data(), part.weights.data() + weight_count))});
  }
  std::vector<std::uint32_t> lengths(part.stored_rows());
  for (std::size_t r = 0; r < lengths.size(); ++r) lengths[r] = part.residual.length(r);
  arrays.push_back(id_array("residual_lengths", types.length_type, lengths));
  arrays.push_back(id_array("residual_lights", types.light_type, part.residual.light_index));
  const std::vector<float>& values = part.residual.values;
  if (types.quantized_residual) {
    const std::vector<std::int32_t> q =
        integers(values.data(), values.size(), part.quantization.residual_step);
    arrays.push_back(
        {"residual_values", "int16", raw_bytes(std::vector<std::int16_t>(q.begin(), q.end()))});
  } else {
    arrays.push_back({"residual_values", "float32", raw_bytes(values)});
  }
  if (types.dark)
    arrays.push_back(bit_set("dark_pixels", part.dark_pixels,
                             std::uint64_t(part.width) * std::uint64_t(part.height)));
  if (types.gains) {
    const std::vector<std::int32_t> q =
        integers(part.dark_gains.data(), part.dark_gains.size(), part.dark_gain_step);
    arrays.push_back(
        {"dark_gains", "int16", raw_bytes(std::vector<std::int16_t>(q.begin(), q.end()))});
  }
  return arrays;
}

nlohmann::ordered_json array_list(const std::vector<BundleArray>& arrays) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const BundleArray& array : arrays)
    list.push_back({{"name", array.name}, {"type", array.type}});
  return list;
}

}  // namespace

WebLayout lay_out_for_web(const CompressedField& field, int residual_cap, int tile_size) {
  validate_compressed_field(field, "cannot publish the compressed field");
  check_residual_cap(residual_cap);
  if (tile_size < 8)
    throw Error("the tile size must be at least 8 pixels, got " + std::to_string(tile_size));

  TileTypes types;
  types.weights = field.coded_weights.empty();
  types.quantized_weights =
      types.weights && multiples_of(field.weights.data(), std::size_t(field.weights.size()),
                                    field.quantization.weight_step);
  types.quantized_residual = multiples_of(
      field.residual.values.data(), field.residual.values.size(), field.quantization.residual_step);
  types.dark = !field.dark_pixels.empty();
  types.gains = types.dark && !field.dark_gains.empty();
  std::uint32_t longest = 0;
  std::uint64_t entries = 0;
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t kept = std::min(field.residual.length(r), std::uint32_t(residual_cap));
    longest = std::max(longest, kept);
    entries += kept;
  }
  types.cluster_type = id_type(std::uint64_t(field.clusters));
  types.length_type = id_type(std::uint64_t(longest) + 1);
  types.light_type = id_type(std::uint64_t(field.lights));

  WebLayout layout;
  nlohmann::ordered_json& shape = layout.field;
  shape["width"] = field.width;
  shape["height"] = field.height;
  shape["channels"] = field.channels;
  shape["lights"] = field.lights;
  shape["terms"] = field.terms;
  shape["clusters"] = field.clusters;
  shape["transform"] = field.transform == BasisTransform::haar ? "haar" : "identity";
  shape["non_negative"] = field.non_negative;
  shape["stored_rows"] = field.stored_rows();
  shape["dark_pixels"] = field.dark_pixels.size();
  shape["weight_step"] = types.quantized_weights ? field.quantization.weight_step : 0.0f;
  shape["residual_step"] = types.quantized_residual ? field.quantization.residual_step : 0.0f;
  shape["dark_gain_step"] = types.gains ? field.dark_gain_step : 0.0f;
  shape["residual_longest_row"] = longest;
  shape["residual_entries"] = entries;

  std::vector<BundleArray> globals;
  const std::vector<float>& scales = field.quantization.basis_scales;
  bool quantized_bases = field.quantization.basis_bits > 0;
  for (std::size_t row = 0; row < scales.size() && quantized_bases; ++row)
    quantized_bases =
        multiples_of(field.basis(0) + row * field.lights, std::size_t(field.lights), scales[row]);
  if (quantized_bases) {
    const std::vector<std::int32_t> q = integers_per_row(field.bases, scales, field.lights);
    globals.push_back({"bases", "int16", raw_bytes(std::vector<std::int16_t>(q.begin(), q.end()))});
    globals.push_back({"basis_scales", "float32", raw_bytes(scales)});
  } else {
    globals.push_back({"bases", "float32", raw_bytes(field.bases)});
  }
  if (types.dark) globals.push_back({"dark_model", "float32", raw_bytes(field.dark)});
  layout.field_file = {{"file", "data/field.bin"}, {"arrays", array_list(globals)}};
  layout.files.push_back({"data/field.bin", bundle_file(globals), field_file_level});
  if (!types.weights) {
    const CodedWeights& coded = field.coded_weights;
    layout.weight_planes = {{"file", "data/weights.j2k"},
                            {"planes", field.channels * field.terms},
                            {"step", coded.step}};
    if (!coded.colour_angles.empty()) layout.weight_planes["colour_angles"] = coded.colour_angles;
    layout.files.push_back({"data/weights.j2k",
                            std::string(coded.codestream.begin(), coded.codestream.end()),
                            weight_planes_level});
  }

  const FieldRegions regions(field);
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  nlohmann::ordered_json tile_array_list;
  for (int level = 0;; ++level) {
    const int stride = 1 << level;
    const int width = (field.width + stride - 1) / stride,
              height = (field.height + stride - 1) / stride;
    const int columns = (width + tile_size - 1) / tile_size,
              rows = (height + tile_size - 1) / tile_size;
    levels.push_back({{"stride", stride},
                      {"width", width},
                      {"height", height},
                      {"columns", columns},
                      {"rows", rows}});
    for (int row = 0; row < rows; ++row)
      for (int column = 0; column < columns; ++column) {
        FieldRegion region;
        region.stride = stride;
        region.x = column * tile_size * stride;
        region.y = row * tile_size * stride;
        region.width = std::min(tile_size, width - column * tile_size);
        region.height = std::min(tile_size, height - row * tile_size);
        const std::vector<BundleArray> arrays =
            tile_arrays(regions.region(region, residual_cap), types);
        if (tile_array_list.is_null()) tile_array_list = array_list(arrays);
        layout.files.push_back({"data/tiles/" + std::to_string(level) + "/" +
                                    std::to_string(column) + "_" + std::to_string(row) + ".bin",
                                bundle_file(arrays), level});
      }
    if (columns == 1 && rows == 1) break;
  }
  layout.tiles = {{"size", tile_size},
                  {"file", "data/tiles/{level}/{column}_{row}.bin"},
                  {"levels", levels},
                  {"arrays", tile_array_list}};
  return layout;
}

}  // namespace relume
