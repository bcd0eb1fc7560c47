// Reading a container: the frame checked (container_format), then each section decoded and
// validated on its own so that an error names the section (docs/container.md).
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "container/container_bit_set.hpp"
#include "container/container_bytes.hpp"
#include "container/container_format.hpp"
#include "container/container_sections.hpp"
#include "container/weight_plane_coding.hpp"
#include "container/weight_prediction.hpp"
#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "model/cluster_terms.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/dark_gains.hpp"
#include "model/quantization.hpp"

namespace relume {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A header is a small JSON object; its free-form parameters are the only unbounded part.
constexpr std::uint64_t max_header_bytes = 16u << 20;

// The most pixels a container may claim (a 32768 x 32768 image). Every other count is bounded by
// the sections that hold its data, hence by the file's size; the mask is not (an all-outside mask
// of any size takes a few bytes of runs), so its size has this sane maximum.
constexpr std::uint64_t max_container_pixels = std::uint64_t(1) << 30;

// What decoding holds at most, for the memory check: the mask (a byte per pixel), the map from
// functions to stored rows of the weight prediction (8 bytes per function) and, per decoded
// section byte, the decoded bytes themselves and up to four bytes of numbers (a 1-byte light index
// becomes a 32-bit one).
constexpr std::uint64_t decoded_bytes_per_section_byte = 5;
constexpr std::uint64_t decoded_bytes_per_function = 8;

std::string read_container_bytes(const fs::path& path) {
  if (!fs::exists(path)) throw Error("container not found: " + path.string());
  if (!fs::is_regular_file(path)) throw Error(path.string() + " is not a relume container file");
  return read_file(path);
}

std::int64_t header_integer(const json& header, const char* key, std::int64_t lowest,
                            std::int64_t highest, const std::string& where) {
  const auto it = header.find(key);
  if (it == header.end() || !it->is_number_integer())
    throw Error(where + ": '" + key + "' is missing or not an integer");
  const std::int64_t value = it->get<std::int64_t>();
  if (value < lowest || value > highest)
    throw Error(where + ": '" + key + "' is " + std::to_string(value) + ", expected " +
                std::to_string(lowest) + " to " + std::to_string(highest));
  return value;
}

std::string header_string(const json& header, const char* key, const std::string& where) {
  const auto it = header.find(key);
  if (it == header.end() || !it->is_string())
    throw Error(where + ": '" + key + "' is missing or not a string");
  return it->get<std::string>();
}

int header_width_bytes(const json& header, const char* key, const std::string& where) {
  const std::int64_t bits = header_integer(header, key, 8, 32, where);
  if (bits != 8 && bits != 16 && bits != 32)
    throw Error(where + ": '" + key + "' is " + std::to_string(bits) + ", expected 8, 16 or 32");
  return static_cast<int>(bits / 8);
}

ValuePrecision header_precision(const json& header, const char* key, std::uint32_t version,
                                const std::string& where) {
  const std::string text = header_string(header, key, where);
  if (text == "float32") return ValuePrecision::float32;
  if (text == "float16") return ValuePrecision::float16;
  if (text == "quantized" && version >= 2) return ValuePrecision::quantized;
  throw Error(where + ": '" + key + "' is \"" + text + "\", expected \"float32\", \"float16\"" +
              (version >= 2 ? " or \"quantized\"" : ""));
}

// A quantization step: a positive finite number when the values are quantized, else 0 (or
// absent, as in version 1).
float header_step(const json& header, const char* key, bool quantized, const std::string& where) {
  const auto it = header.find(key);
  const double step = it == header.end() ? 0.0 : it->is_number() ? it->get<double>() : -1.0;
  const bool valid = quantized ? std::isfinite(step) && step > 0 && step < 3.4e38 : step == 0;
  if (!valid)
    throw Error(where + ": '" + key + "' is " + (it == header.end() ? "missing" : it->dump()) +
                (quantized ? ", expected a positive step for quantized values"
                           : ", expected 0 for values that are not quantized"));
  return float(step);
}

float get_value(ByteReader& in, ValuePrecision precision) {
  return precision == ValuePrecision::float16 ? half_bits_to_float(in.u16()) : in.f32();
}

struct DecodedHeader {
  bool weight_planes = false;  // W is coded as planes (version 5 on)
  std::uint64_t stored_rows = 0;
  std::uint64_t nonzeros = 0;
  StoredWidths widths{};
  ContainerOptions options;
};

class ContainerDecoder {
 public:
  ContainerDecoder(const std::string& bytes, const ParsedContainer& parsed, const fs::path& path)
      : bytes_(bytes), parsed_(parsed), file_(path.string()) {}

  CompressedField decode(ContainerOptions* stored_options) {
    CompressedField field;
    const DecodedHeader header = decode_header(field);
    decode_lights(field);
    check_row_section_sizes(field, header);
    decode_mask(field);
    decode_functions(field, header);
    if (parsed_.layout.version >= 2) decode_dark(field);
    decode_clusters(field, header);
    decode_bases(field);
    decode_weights(field, header);
    decode_residual(field, header);
    if (stored_options) {
      *stored_options = header.options;
      stored_options->entropy_coding = false;
      for (const SectionCoding& coding : parsed_.codings)
        stored_options->entropy_coding = stored_options->entropy_coding || coding.zstd;
    }
    return field;
  }

 private:
  std::string where(std::string_view section) const {
    return file_ + ": section '" + std::string(section) + "'";
  }

  // A reader of a section's decoded bytes, which may not be more than `raw_limit`. The bytes are
  // decoded once and kept while the decoder lives.
  ByteReader reader(std::string_view section, std::uint64_t raw_limit) const {
    auto [it, inserted] = decoded_.try_emplace(std::string(section));
    if (inserted) it->second = parsed_.contents(bytes_, section, raw_limit, file_);
    return ByteReader(it->second, where(section));
  }

  // A reader for a section whose size follows from the header; fails unless it is exactly that.
  ByteReader sized_reader(std::string_view section,
                          std::initializer_list<std::uint64_t> factors) const {
    const std::uint64_t expected = checked_product(factors, where(section));
    ByteReader in = reader(section, expected);
    if (in.remaining() != expected)
      in.fail("has " + std::to_string(in.remaining()) + " bytes, the header implies " +
              std::to_string(expected));
    return in;
  }

  // The most bytes a position set over `universe` positions is stored in: the writer takes the
  // smaller of a bitmap and runs, so never more than the bitmap with its leading byte.
  static std::uint64_t bit_set_limit(std::uint64_t universe) { return 1 + (universe + 7) / 8; }

  // The sections whose sizes follow from the header's row and entry counts, checked before anything
  // is allocated: this bounds the stored rows and residual entries by the file's size.
  void check_row_section_sizes(const CompressedField& field, const DecodedHeader& header) const {
    const std::uint64_t rows = header.stored_rows;
    sized_reader("clusters", {rows, std::uint64_t(header.widths.cluster_id_bytes)});
    // From version 3 the weights of unused basis rows are left out (decode_weights checks the
    // exact size); every version's weights fit stored rows x terms values.
    const std::uint64_t all_weights_bytes = checked_product(
        {rows, std::uint64_t(field.terms), std::uint64_t(value_bytes(header.options.weights))},
        where("weights"));
    if (header.weight_planes)
      sized_reader("weights", {0});
    else if (parsed_.layout.version >= 3)
      reader("weights", all_weights_bytes);
    else
      sized_reader("weights", {all_weights_bytes});
    sized_reader("residual_offsets", {rows, std::uint64_t(header.widths.residual_length_bytes)});
    sized_reader("residual_indices",
                 {header.nonzeros, std::uint64_t(header.widths.light_index_bytes)});
    sized_reader("residual_values",
                 {header.nonzeros, std::uint64_t(value_bytes(header.options.residual))});
  }

  DecodedHeader decode_header(CompressedField& field) const {
    const std::string at = where("header");
    const ByteReader in = reader("header", max_header_bytes);
    json header;
    try {
      header = json::parse(in.rest());
    } catch (const json::exception& e) {
      throw Error(at + ": not valid JSON: " + e.what());
    }
    if (!header.is_object()) throw Error(at + ": not a JSON object");
    constexpr std::int64_t int_max = std::numeric_limits<int>::max();
    field.width = int(header_integer(header, "width", 1, int_max, at));
    field.height = int(header_integer(header, "height", 1, int_max, at));
    field.channels = int(header_integer(header, "channels", 1, int_max, at));
    field.lights = int(header_integer(header, "lights", 1, int_max, at));
    field.terms = int(header_integer(header, "terms", 0, int_max, at));
    field.clusters = int(header_integer(header, "clusters", 0, int_max, at));
    const std::string transform = header_string(header, "transform", at);
    if (transform == "identity")
      field.transform = BasisTransform::identity;
    else if (transform == "haar")
      field.transform = BasisTransform::haar;
    else
      throw Error(at + ": 'transform' is \"" + transform + "\", expected \"identity\" or \"haar\"");
    // v1 files and the first v2 files have no 'non_negative': not known to be non-negative.
    if (const auto non_negative = header.find("non_negative"); non_negative != header.end()) {
      if (!non_negative->is_boolean()) throw Error(at + ": 'non_negative' is not true or false");
      field.non_negative = non_negative->get<bool>();
    }
    check_dimensions(field, at);
    const std::uint64_t pixels = std::uint64_t(field.width) * std::uint64_t(field.height);
    if (pixels > max_container_pixels)
      throw Error(at + ": " + std::to_string(field.width) + "x" + std::to_string(field.height) +
                  " pixels is more than the " + std::to_string(max_container_pixels) +
                  " a container may hold");
    std::uint64_t section_bytes = 0;
    for (const ContainerSection& section : parsed_.layout.sections)
      section_bytes += section.raw_bytes;
    check_memory_need(pixels + decoded_bytes_per_function * std::uint64_t(field.functions()) +
                          decoded_bytes_per_section_byte * section_bytes,
                      "reading " + file_ + " (" + std::to_string(field.width) + "x" +
                          std::to_string(field.height) + " pixels)");

    DecodedHeader decoded;
    decoded.stored_rows =
        std::uint64_t(header_integer(header, "stored_rows", 0, field.functions(), at));
    decoded.nonzeros = std::uint64_t(header_integer(header, "residual_nonzeros", 0,
                                                    std::numeric_limits<std::uint32_t>::max(), at));
    const std::uint32_t version = parsed_.layout.version;
    decoded.options.weights = header_precision(header, "weights_precision", version, at);
    decoded.options.residual = header_precision(header, "residual_precision", version, at);
    ValueQuantization& quantization = field.quantization;
    quantization.weight_step = header_step(
        header, "weight_step", decoded.options.weights == ValuePrecision::quantized, at);
    quantization.residual_step = header_step(
        header, "residual_step", decoded.options.residual == ValuePrecision::quantized, at);
    if (version >= 2) {
      quantization.basis_bits = int(header_integer(header, "basis_bits", 0, 16, at));
      if (quantization.basis_bits > 0 && quantization.basis_bits < 8)
        throw Error(at + ": 'basis_bits' is " + std::to_string(quantization.basis_bits) +
                    ", expected 0 (float32 bases) or 8 to 16");
    }
    if (version >= 4) {
      const auto step = header.find("dark_gain_step");
      const double value = step != header.end() && step->is_number() ? step->get<double>() : -1;
      if (!std::isfinite(value) || value < 0 || value > 3.4e38)
        throw Error(at + ": 'dark_gain_step' is " +
                    (step == header.end() ? std::string("missing") : step->dump()) +
                    ", expected 0 (no gains) or a positive step");
      field.dark_gain_step = float(value);
      const std::int64_t block = header_integer(header, "dark_gain_block", 1, 1 << 16, at);
      if (block != dark_gain_block)
        throw Error(at + ": 'dark_gain_block' is " + std::to_string(block) +
                    ", this relume reads gains per " + std::to_string(dark_gain_block) +
                    " pixel blocks");
    }
    if (version >= 5) {
      const std::string coding = header_string(header, "weight_coding", at);
      if (coding != "values" && coding != "jpeg2000_planes")
        throw Error(at + ": 'weight_coding' is \"" + coding +
                    "\", expected \"values\" or \"jpeg2000_planes\"");
      decoded.weight_planes = coding == "jpeg2000_planes";
      field.coded_weights.step = header_step(header, "weight_planes_step", decoded.weight_planes, at);
      if (decoded.weight_planes && decoded.options.weights != ValuePrecision::float32)
        throw Error(at + ": weights coded as planes have the precision \"float32\", the header "
                    "says \"" + to_string(decoded.options.weights) + "\"");
    }
    decoded.widths.cluster_id_bytes = header_width_bytes(header, "cluster_id_bits", at);
    decoded.widths.residual_length_bytes = header_width_bytes(header, "residual_length_bits", at);
    decoded.widths.light_index_bytes = header_width_bytes(header, "light_index_bits", at);
    decoded.options.light_index = decoded.widths.light_index_bytes == 1   ? IndexWidth::bits8
                                  : decoded.widths.light_index_bytes == 2 ? IndexWidth::bits16
                                                                          : IndexWidth::bits32;
    const auto parameters = header.find("parameters");
    if (parameters == header.end() || !parameters->is_object())
      throw Error(at + ": 'parameters' is missing or not a JSON object");
    decoded.options.parameters_json = parameters->dump();
    const auto software = header.find("software");
    if (software != header.end()) {
      if (!software->is_string()) throw Error(at + ": 'software' is not a string");
      decoded.options.written_by = software->get<std::string>();
    }
    return decoded;
  }

  void decode_lights(CompressedField& field) const {
    ByteReader in = sized_reader("lights", {2, std::uint64_t(field.lights), 3, 4});
    field.directions.resize(field.lights, 3);
    field.intensities.resize(field.lights, 3);
    for (LightRgb* rows : {&field.directions, &field.intensities})
      for (int i = 0; i < field.lights; ++i)
        for (int c = 0; c < 3; ++c) (*rows)(i, c) = in.f32();
    check_lights(field, where("lights"));
  }

  void decode_mask(CompressedField& field) const {
    const std::uint64_t pixels = std::uint64_t(field.width) * field.height;
    ByteReader in = reader("mask", bit_set_limit(pixels));
    field.mask = decode_bit_mask(in, pixels);
  }

  void decode_functions(CompressedField& field, const DecodedHeader& header) const {
    ByteReader in = reader("functions", bit_set_limit(std::uint64_t(field.functions())));
    const std::vector<std::uint64_t> functions =
        decode_bit_set(in, field.functions(), header.stored_rows);
    if (functions.size() != header.stored_rows)
      in.fail("holds " + std::to_string(functions.size()) + " functions, the header says " +
              std::to_string(header.stored_rows) + " stored rows");
    field.stored_function.assign(functions.begin(), functions.end());
  }

  void decode_dark(CompressedField& field) const {
    const std::uint64_t pixels = std::uint64_t(field.width) * field.height;
    ByteReader set = reader("dark_pixels", bit_set_limit(pixels));
    const std::vector<std::uint64_t> dark = decode_bit_set(set, pixels, pixels);
    field.dark_pixels.assign(dark.begin(), dark.end());
    check_dark_pixels(field, where("dark_pixels"));
    ByteReader values = sized_reader(
        "dark", {dark.empty() ? 0 : std::uint64_t(field.channels), std::uint64_t(field.lights), 4});
    field.dark.resize(values.remaining() / 4);
    for (float& v : field.dark) v = values.f32();
    check_dark_values(field, where("dark"));
    if (parsed_.layout.version >= 4) decode_dark_gains(field);
  }

  // Version 4: the gains' block grid when the header gives a step and a pixel is dark, else none.
  void decode_dark_gains(CompressedField& field) const {
    const bool stored = field.dark_gain_step > 0 && !field.dark_pixels.empty();
    DarkGainGrid grid = empty_dark_gain_grid(field.width, field.height, field.channels);
    ByteReader in = sized_reader("dark_gains", {stored ? grid.values.size() : 0, 2});
    if (!stored) return;
    for (std::int32_t& value : grid.values) {
      value = in.u16();
      if (value > max_quantized_gain)
        in.fail("holds the gain " + std::to_string(value) + " steps, expected at most " +
                std::to_string(max_quantized_gain));
    }
    expand_dark_gains(field, grid);
    check_dark_gains(field, where("dark_gains"));
  }

  void decode_clusters(CompressedField& field, const DecodedHeader& header) const {
    ByteReader in = sized_reader(
        "clusters", {header.stored_rows, std::uint64_t(header.widths.cluster_id_bytes)});
    field.cluster.resize(header.stored_rows);
    for (std::uint32_t& k : field.cluster)
      k = static_cast<std::uint32_t>(in.unsigned_of_width(header.widths.cluster_id_bytes));
    check_clusters(field, where("clusters"));
  }

  void decode_bases(CompressedField& field) const {
    ValueQuantization& quantization = field.quantization;
    const int bytes = basis_value_bytes(quantization.basis_bits);
    const std::uint64_t rows = std::uint64_t(field.clusters) * std::uint64_t(field.terms);
    if (parsed_.layout.version >= 2) {
      ByteReader scales = sized_reader("basis_scales", {quantization.basis_bits ? rows : 0, 4});
      quantization.basis_scales.resize(scales.remaining() / 4);
      for (float& scale : quantization.basis_scales) {
        scale = scales.f32();
        if (!(std::isfinite(scale) && scale > 0))
          scales.fail("holds the scale " + std::to_string(scale) + ", expected a positive number");
      }
    }
    ByteReader in =
        sized_reader("bases", {rows, std::uint64_t(field.lights), std::uint64_t(bytes)});
    field.bases.resize(in.remaining() / std::size_t(bytes));
    for (std::size_t v = 0; v < field.bases.size(); ++v) {
      if (bytes == 4) {
        field.bases[v] = in.f32();
        continue;
      }
      const double q = bytes == 1 ? double(std::int8_t(in.u8())) : double(std::int16_t(in.u16()));
      if (std::abs(q) >= std::ldexp(1.0, quantization.basis_bits - 1))
        in.fail("holds the integer " + std::to_string(q) + ", beyond " +
                std::to_string(quantization.basis_bits) + " bits");
      field.bases[v] = float(q * quantization.basis_scales[v / std::size_t(field.lights)]);
    }
    check_bases(field, where("bases"));
  }

  // A quantized value: a 16-bit integer in [-32767, 32767] times the step.
  static float quantized_value(ByteReader& in, float step) {
    const std::int16_t q = std::int16_t(in.u16());
    if (q < -max_quantized_value) in.fail("holds the integer -32768, beyond the quantized range");
    return float(double(q) * step);
  }

  // Which terms' weights the rows of each cluster store (k * terms + j): from version 3 those of
  // the used basis rows (model/cluster_terms.hpp), before that all.
  std::vector<std::uint8_t> stored_terms(const CompressedField& field) const {
    if (parsed_.layout.version >= 3) return used_basis_rows(field);
    return std::vector<std::uint8_t>(std::size_t(field.clusters) * field.terms, 1);
  }

  void decode_weights(CompressedField& field, const DecodedHeader& header) const {
    if (parsed_.layout.version >= 5) decode_weight_planes_section(field, header);
    if (header.weight_planes) return;
    const std::vector<std::uint8_t> stored = stored_terms(field);
    ByteReader in = sized_reader("weights", {stored_weight_count(field, stored),
                                             std::uint64_t(value_bytes(header.options.weights))});
    field.weights.setZero(Eigen::Index(header.stored_rows), field.terms);
    if (header.options.weights == ValuePrecision::quantized) {
      std::vector<std::uint16_t> errors(in.remaining() / 2);
      for (std::uint16_t& error : errors) error = in.u16();
      const std::vector<std::int32_t> integers = unpredict_weights(field, errors, stored);
      for (std::size_t i = 0; i < integers.size(); ++i) {
        if (integers[i] < -max_quantized_value)
          in.fail("predicts the integer -32768 for " + weight_text(i, field.terms) +
                  ", beyond the quantized range");
        field.weights.data()[i] = float(double(integers[i]) * field.quantization.weight_step);
      }
    } else {
      for (std::uint64_t r = 0; r < header.stored_rows; ++r)
        for (int j = 0; j < field.terms; ++j)
          if (stored[std::size_t(field.cluster[r]) * field.terms + j])
            field.weights(Eigen::Index(r), j) = get_value(in, header.options.weights);
    }
    check_weights(field, where("weights"));
  }

  // Version 6, with weight planes: each term's colour transform as three int16 angles, or an
  // empty section (every term the fixed transform, as before version 6); only for three channels.
  void decode_weight_colour(CompressedField& field) const {
    if (parsed_.layout.version < 6) return;
    ByteReader in = reader("weight_colour", 6 * std::uint64_t(field.terms));
    if (in.remaining() == 0) return;
    if (field.channels != 3)
      in.fail("holds colour transforms for a field of " + std::to_string(field.channels) +
              " channels (only three channels have them)");
    if (in.remaining() != 6 * std::uint64_t(field.terms))
      in.fail("has " + std::to_string(in.remaining()) + " bytes, three angles of 2 bytes for " +
              std::to_string(field.terms) + " terms are " + std::to_string(6 * field.terms));
    field.coded_weights.colour_angles.resize(3 * std::size_t(field.terms));
    for (std::int16_t& angle : field.coded_weights.colour_angles) {
      angle = std::int16_t(in.u16());
      if (angle == -32768) in.fail("holds the angle -32768, outside -32767 to 32767");
    }
  }

  // Version 5: the codestream of W's planes when the header says W is coded so (decoded into W
  // here), else an empty section (and from version 6 an empty weight_colour section).
  void decode_weight_planes_section(CompressedField& field, const DecodedHeader& header) const {
    if (!header.weight_planes) {
      sized_reader("weight_planes", {0});
      if (parsed_.layout.version >= 6) sized_reader("weight_colour", {0});
      return;
    }
    const std::string at = where("weight_planes");
    const std::uint64_t samples = checked_product(
        {std::uint64_t(field.channels), std::uint64_t(field.terms), std::uint64_t(field.width),
         std::uint64_t(field.height)},
        at);
    if (samples == 0) throw Error(at + ": a field without terms has no weight planes");
    // OpenJPEG's planes, the integers and the floats: 12 bytes a sample.
    check_memory_need(12 * samples, "decoding the weight planes of " + file_);
    // A codestream is at most a little larger than its 16-bit samples.
    const ByteReader in = reader("weight_planes", 2 * samples + (1u << 20));
    const std::string_view codestream = in.rest();
    field.coded_weights.codestream.assign(codestream.begin(), codestream.end());
    decode_weight_colour(field);
    decode_weight_planes(field, 0, at);
    check_weights(field, at);
  }

  void decode_residual(CompressedField& field, const DecodedHeader& header) const {
    ResidualRows& e = field.residual;
    ByteReader lengths =
        sized_reader("residual_offsets",
                     {header.stored_rows, std::uint64_t(header.widths.residual_length_bytes)});
    e.row_offsets.assign(1, 0);
    std::uint64_t total = 0;
    for (std::uint64_t r = 0; r < header.stored_rows; ++r) {
      total += lengths.unsigned_of_width(header.widths.residual_length_bytes);
      if (total > header.nonzeros)
        lengths.fail("the rows up to " + stored_row_name(r) + " hold " + std::to_string(total) +
                     " residual entries, the header says " + std::to_string(header.nonzeros) +
                     " in all");
      e.row_offsets.push_back(static_cast<std::uint32_t>(total));
    }
    if (total != header.nonzeros)
      lengths.fail("the rows hold " + std::to_string(total) +
                   " residual entries, the header says " + std::to_string(header.nonzeros));

    ByteReader indices = sized_reader(
        "residual_indices", {header.nonzeros, std::uint64_t(header.widths.light_index_bytes)});
    e.light_index.resize(header.nonzeros);
    for (std::uint32_t& i : e.light_index)
      i = static_cast<std::uint32_t>(indices.unsigned_of_width(header.widths.light_index_bytes));
    check_residual_indices(field, where("residual_indices"));

    ByteReader values = sized_reader(
        "residual_values", {header.nonzeros, std::uint64_t(value_bytes(header.options.residual))});
    e.values.resize(header.nonzeros);
    for (float& v : e.values)
      v = header.options.residual == ValuePrecision::quantized
              ? quantized_value(values, field.quantization.residual_step)
              : get_value(values, header.options.residual);
    check_residual_values(field, where("residual_values"));
  }

  const std::string& bytes_;
  const ParsedContainer& parsed_;
  std::string file_;
  mutable std::map<std::string, std::string> decoded_;
};

}  // namespace

CompressedField decode_container(const std::string& bytes, const fs::path& path,
                                 ContainerOptions* stored_options) {
  const ParsedContainer parsed = parse_container(bytes, path);
  return ContainerDecoder(bytes, parsed, path).decode(stored_options);
}

CompressedField read_container(const fs::path& path, ContainerOptions* stored_options) {
  return decode_container(read_container_bytes(path), path, stored_options);
}

ContainerLayout describe_container(const fs::path& path) {
  return parse_container(read_container_bytes(path), path).layout;
}

}  // namespace relume
