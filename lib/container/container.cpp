// Writing, reading and validating .relume containers (see container.hpp and docs/container.md).
#include "container/container.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/version.hpp>

#include "container/container_bit_set.hpp"
#include "container/container_bytes.hpp"
#include "container/crc32.hpp"
#include "core/atomic_file.hpp"
#include "model/compressed_field_checks.hpp"

namespace relume {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::string_view container_magic{"RELUME\0\0", 8};
constexpr std::array<std::string_view, 10> section_names{
    "header",           "lights",         "mask",    "functions",
    "clusters",         "bases",          "weights", "residual_offsets",
    "residual_indices", "residual_values"};
constexpr std::size_t section_name_bytes = 16;
constexpr std::size_t table_entry_bytes = section_name_bytes + 8 + 8 + 4 + 4;
constexpr std::size_t fixed_preamble_bytes =
    container_magic.size() + 4 + 4;  // magic, version, count
constexpr std::uint64_t preamble_bytes =
    fixed_preamble_bytes + section_names.size() * table_entry_bytes + 4;  // + table CRC

std::string hex32(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

// Bytes of the smallest of u8 / u16 / u32 that holds values up to max_value.
int bytes_for_max_value(std::uint64_t max_value) {
  return max_value <= 0xFFu ? 1 : max_value <= 0xFFFFu ? 2 : 4;
}

std::uint64_t checked_product(std::initializer_list<std::uint64_t> factors,
                              const std::string& where) {
  std::uint64_t product = 1;
  for (std::uint64_t f : factors)
    if (__builtin_mul_overflow(product, f, &product))
      throw Error(where + ": sizes overflow 64 bits");
  return product;
}

// ---- Encoding ----

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

struct StoredWidths {
  int cluster_id_bytes;
  int residual_length_bytes;
  int light_index_bytes;
};

StoredWidths stored_widths(const CompressedField& field, IndexWidth light_index) {
  return {bytes_for_max_value(field.clusters > 0 ? field.clusters - 1 : 0),
          bytes_for_max_value(field.residual.longest_row()), index_width_bits(light_index) / 8};
}

struct EncodedContainer {
  std::string bytes;
  ContainerLayout layout;
};

EncodedContainer encode_container(const CompressedField& field, const ContainerOptions& options,
                                  const std::string& where) {
  validate_compressed_field(field, where);
  IndexWidth light_index;
  try {
    light_index = resolve_light_index_width(options.light_index, field.lights);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  const StoredWidths widths = stored_widths(field, light_index);
  const std::size_t rows = field.stored_rows();
  std::array<std::string, section_names.size()> sections;

  json header = {{"width", field.width},
                 {"height", field.height},
                 {"channels", field.channels},
                 {"lights", field.lights},
                 {"terms", field.terms},
                 {"clusters", field.clusters},
                 {"transform", field.transform == BasisTransform::haar ? "haar" : "identity"},
                 {"stored_rows", rows},
                 {"residual_nonzeros", field.residual.nonzeros()},
                 {"weights_precision", to_string(options.weights)},
                 {"residual_precision", to_string(options.residual)},
                 {"cluster_id_bits", 8 * widths.cluster_id_bytes},
                 {"residual_length_bits", 8 * widths.residual_length_bytes},
                 {"light_index_bits", 8 * widths.light_index_bytes},
                 {"parameters", parse_parameters(options.parameters_json, where)},
                 {"software", version_line()}};
  sections[0] = header.dump();

  ByteWriter lights;
  for (const LightRgb* rows_of : {&field.directions, &field.intensities})
    for (Eigen::Index i = 0; i < field.lights; ++i)
      for (int c = 0; c < 3; ++c) lights.f32((*rows_of)(i, c));
  sections[1] = lights.take();

  std::vector<std::uint64_t> inside;
  for (std::size_t q = 0; q < field.mask.size(); ++q)
    if (field.mask[q]) inside.push_back(q);
  sections[2] = encode_bit_set(inside, field.mask.size());
  sections[3] = encode_bit_set(
      std::vector<std::uint64_t>(field.stored_function.begin(), field.stored_function.end()),
      std::uint64_t(field.functions()));

  ByteWriter clusters;
  for (std::uint32_t k : field.cluster) clusters.unsigned_of_width(k, widths.cluster_id_bytes);
  sections[4] = clusters.take();

  ByteWriter bases;
  for (float v : field.bases) bases.f32(v);
  sections[5] = bases.take();

  // W is row-major: stored rows x terms.
  sections[6] = encode_values(
      field.weights.data(), std::size_t(field.weights.size()), options.weights,
      [&](std::size_t i) { return weight_text(i, field.terms); }, where);

  const ResidualRows& e = field.residual;
  ByteWriter lengths, indices;
  for (std::size_t r = 0; r < rows; ++r)
    lengths.unsigned_of_width(e.length(r), widths.residual_length_bytes);
  for (std::uint32_t light : e.light_index)
    indices.unsigned_of_width(light, widths.light_index_bytes);
  sections[7] = lengths.take();
  sections[8] = indices.take();
  sections[9] = encode_values(
      e.values.data(), e.values.size(), options.residual,
      [&](std::size_t k) { return residual_entry_text(e, k); }, where);

  EncodedContainer encoded;
  ContainerLayout& layout = encoded.layout;
  layout.preamble_bytes = preamble_bytes;
  std::uint64_t offset = preamble_bytes;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    layout.sections.push_back(
        {std::string(section_names[s]), offset, sections[s].size(), crc32(sections[s])});
    offset += sections[s].size();
  }
  layout.file_bytes = offset;

  ByteWriter file;
  file.bytes(container_magic);
  file.u32(container_format_version);
  file.u32(static_cast<std::uint32_t>(sections.size()));
  for (const ContainerSection& section : layout.sections) {
    std::string name = section.name;
    name.resize(section_name_bytes, '\0');
    file.bytes(name);
    file.u64(section.offset);
    file.u64(section.bytes);
    file.u32(section.crc32);
    file.u32(0);  // reserved
  }
  file.u32(crc32(file.data()));
  for (const std::string& section : sections) file.bytes(section);
  encoded.bytes = file.take();
  return encoded;
}

// ---- Decoding ----

std::string first_bytes_text(const std::string& bytes) {
  std::string text;
  for (std::size_t i = 0; i < std::min<std::size_t>(bytes.size(), 8); ++i) {
    char hex[4];
    std::snprintf(hex, sizeof hex, "%02X ", static_cast<unsigned char>(bytes[i]));
    text += hex;
  }
  if (!text.empty()) text.pop_back();
  return text;
}

// Checks magic, version, section table and every checksum; returns the layout.
ContainerLayout parse_layout(const std::string& bytes, const fs::path& path) {
  const std::string file = path.string();
  if (bytes.empty()) throw Error(file + " is empty, not a relume container");
  const std::string_view head = std::string_view(bytes).substr(0, container_magic.size());
  if (head != container_magic.substr(0, head.size()))
    throw Error(file + " is not a relume container: it starts with bytes " +
                first_bytes_text(bytes) +
                ", expected the magic \"RELUME\\0\\0\" (52 45 4C 55 4D 45 00 00)");
  if (bytes.size() < fixed_preamble_bytes)
    throw Error(file + " is truncated: it has " + std::to_string(bytes.size()) +
                " bytes, fewer than the " + std::to_string(fixed_preamble_bytes) +
                " of a container's magic, version and section count");
  ByteReader preamble(bytes, file + ": section table");
  preamble.bytes(container_magic.size());
  ContainerLayout layout;
  layout.version = preamble.u32();
  if (layout.version != container_format_version)
    throw Error(file + ": container format version " + std::to_string(layout.version) +
                " is not supported (this relume reads version " +
                std::to_string(container_format_version) + ")");
  const std::uint32_t count = preamble.u32();
  if (count != section_names.size())
    throw Error(file + ": the section table is corrupt: it lists " + std::to_string(count) +
                " sections, format version 1 has " + std::to_string(section_names.size()));
  if (bytes.size() < preamble_bytes)
    throw Error(file + " is truncated: the section table needs " + std::to_string(preamble_bytes) +
                " bytes, the file has " + std::to_string(bytes.size()));
  const std::uint32_t computed_table_crc = crc32(bytes.data(), preamble_bytes - 4);
  layout.preamble_bytes = preamble_bytes;
  layout.file_bytes = bytes.size();
  std::vector<std::uint32_t> reserved;
  for (std::size_t s = 0; s < count; ++s) {
    ContainerSection section;
    const std::string_view name = preamble.bytes(section_name_bytes);
    section.name = std::string(name.substr(0, name.find('\0')));
    section.offset = preamble.u64();
    section.bytes = preamble.u64();
    section.crc32 = preamble.u32();
    reserved.push_back(preamble.u32());
    layout.sections.push_back(section);
  }
  const std::uint32_t stored_table_crc = preamble.u32();
  if (stored_table_crc != computed_table_crc)
    throw Error(file + ": the section table is corrupt (CRC-32 " + hex32(computed_table_crc) +
                ", the file says " + hex32(stored_table_crc) + ")");

  std::uint64_t expected_offset = preamble_bytes;
  for (std::size_t s = 0; s < count; ++s) {
    const ContainerSection& section = layout.sections[s];
    if (section.name != section_names[s])
      throw Error(file + ": section " + std::to_string(s) + " is named '" + section.name +
                  "', expected '" + std::string(section_names[s]) + "'");
    if (reserved[s] != 0)
      throw Error(file + ": section '" + section.name + "' has reserved field " +
                  hex32(reserved[s]) + " in the section table, expected 0");
    if (section.offset != expected_offset)
      throw Error(file + ": section '" + section.name + "' starts at byte " +
                  std::to_string(section.offset) + ", expected " + std::to_string(expected_offset));
    if (section.bytes > bytes.size() || section.offset > bytes.size() - section.bytes)
      throw Error(file + " is truncated: section '" + section.name + "' needs bytes " +
                  std::to_string(section.offset) + " to " +
                  std::to_string(section.offset + section.bytes) + ", the file has " +
                  std::to_string(bytes.size()));
    const std::uint32_t computed = crc32(bytes.data() + section.offset, section.bytes);
    if (computed != section.crc32)
      throw Error(file + ": section '" + section.name + "' is corrupt (CRC-32 " + hex32(computed) +
                  ", the section table says " + hex32(section.crc32) + ")");
    expected_offset = section.offset + section.bytes;
  }
  if (expected_offset != bytes.size())
    throw Error(file + " has " + std::to_string(bytes.size() - expected_offset) +
                " unexpected bytes after its last section");
  return layout;
}

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

ValuePrecision header_precision(const json& header, const char* key, const std::string& where) {
  const std::string text = header_string(header, key, where);
  if (text == "float32") return ValuePrecision::float32;
  if (text == "float16") return ValuePrecision::float16;
  throw Error(where + ": '" + key + "' is \"" + text + "\", expected \"float32\" or \"float16\"");
}

float get_value(ByteReader& in, ValuePrecision precision) {
  return precision == ValuePrecision::float16 ? half_bits_to_float(in.u16()) : in.f32();
}

int value_bytes(ValuePrecision precision) { return precision == ValuePrecision::float16 ? 2 : 4; }

struct DecodedHeader {
  std::uint64_t stored_rows = 0;
  std::uint64_t nonzeros = 0;
  StoredWidths widths{};
  ContainerOptions options;
};

class ContainerDecoder {
 public:
  ContainerDecoder(const std::string& bytes, const ContainerLayout& layout, const fs::path& path)
      : bytes_(bytes), layout_(layout), file_(path.string()) {}

  CompressedField decode(ContainerOptions* stored_options) {
    CompressedField field;
    const DecodedHeader header = decode_header(field);
    decode_lights(field);
    check_row_section_sizes(field, header);
    decode_mask(field);
    decode_functions(field, header);
    decode_clusters(field, header);
    decode_bases(field);
    decode_weights(field, header);
    decode_residual(field, header);
    if (stored_options) *stored_options = header.options;
    return field;
  }

 private:
  std::string where(std::string_view section) const {
    return file_ + ": section '" + std::string(section) + "'";
  }

  ByteReader reader(std::string_view section) const {
    const ContainerSection& s = layout_.section(section);
    return ByteReader(std::string_view(bytes_).substr(s.offset, s.bytes), where(section));
  }

  // A reader for a section whose size follows from the header; fails unless it is exactly that.
  ByteReader sized_reader(std::string_view section,
                          std::initializer_list<std::uint64_t> factors) const {
    ByteReader in = reader(section);
    const std::uint64_t expected = checked_product(factors, where(section));
    if (in.remaining() != expected)
      in.fail("has " + std::to_string(in.remaining()) + " bytes, the header implies " +
              std::to_string(expected));
    return in;
  }

  // The sections whose sizes follow from the header's row and entry counts, checked before anything
  // is allocated: this bounds the stored rows and residual entries by the file's size.
  void check_row_section_sizes(const CompressedField& field, const DecodedHeader& header) const {
    const std::uint64_t rows = header.stored_rows;
    sized_reader("clusters", {rows, std::uint64_t(header.widths.cluster_id_bytes)});
    sized_reader("weights", {rows, std::uint64_t(field.terms),
                             std::uint64_t(value_bytes(header.options.weights))});
    sized_reader("residual_offsets", {rows, std::uint64_t(header.widths.residual_length_bytes)});
    sized_reader("residual_indices",
                 {header.nonzeros, std::uint64_t(header.widths.light_index_bytes)});
    sized_reader("residual_values",
                 {header.nonzeros, std::uint64_t(value_bytes(header.options.residual))});
  }

  DecodedHeader decode_header(CompressedField& field) const {
    const std::string at = where("header");
    const ContainerSection& s = layout_.section("header");
    json header;
    try {
      header = json::parse(bytes_.begin() + std::ptrdiff_t(s.offset),
                           bytes_.begin() + std::ptrdiff_t(s.offset + s.bytes));
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
    check_dimensions(field, at);

    DecodedHeader decoded;
    decoded.stored_rows =
        std::uint64_t(header_integer(header, "stored_rows", 0, field.functions(), at));
    decoded.nonzeros = std::uint64_t(header_integer(header, "residual_nonzeros", 0,
                                                    std::numeric_limits<std::uint32_t>::max(), at));
    decoded.options.weights = header_precision(header, "weights_precision", at);
    decoded.options.residual = header_precision(header, "residual_precision", at);
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
    ByteReader in = reader("mask");
    field.mask = decode_bit_mask(in, std::uint64_t(field.width) * field.height);
  }

  void decode_functions(CompressedField& field, const DecodedHeader& header) const {
    ByteReader in = reader("functions");
    const std::vector<std::uint64_t> functions =
        decode_bit_set(in, field.functions(), header.stored_rows);
    if (functions.size() != header.stored_rows)
      in.fail("holds " + std::to_string(functions.size()) + " functions, the header says " +
              std::to_string(header.stored_rows) + " stored rows");
    field.stored_function.assign(functions.begin(), functions.end());
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
    ByteReader in =
        sized_reader("bases", {std::uint64_t(field.clusters), std::uint64_t(field.terms),
                               std::uint64_t(field.lights), 4});
    field.bases.resize(in.remaining() / 4);
    for (float& v : field.bases) v = in.f32();
    check_bases(field, where("bases"));
  }

  void decode_weights(CompressedField& field, const DecodedHeader& header) const {
    ByteReader in = sized_reader("weights", {header.stored_rows, std::uint64_t(field.terms),
                                             std::uint64_t(value_bytes(header.options.weights))});
    field.weights.resize(Eigen::Index(header.stored_rows), field.terms);
    for (std::uint64_t r = 0; r < header.stored_rows; ++r)
      for (int j = 0; j < field.terms; ++j)
        field.weights(Eigen::Index(r), j) = get_value(in, header.options.weights);
    check_weights(field, where("weights"));
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
    for (float& v : e.values) v = get_value(values, header.options.residual);
    check_residual_values(field, where("residual_values"));
  }

  const std::string& bytes_;
  const ContainerLayout& layout_;
  std::string file_;
};

}  // namespace

ValuePrecision parse_value_precision(const std::string& name) {
  if (name == "float32") return ValuePrecision::float32;
  if (name == "float16" || name == "half") return ValuePrecision::float16;
  throw Error("unknown precision \"" + name + "\": expected float32 or float16 (half)");
}

std::string to_string(ValuePrecision precision) {
  return precision == ValuePrecision::float16 ? "float16" : "float32";
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

void write_container(const fs::path& path, const CompressedField& field,
                     const ContainerOptions& options) {
  const EncodedContainer encoded =
      encode_container(field, options, "cannot write " + path.string());
  write_file_atomically(path, encoded.bytes);
}

ContainerLayout plan_container(const CompressedField& field, const ContainerOptions& options) {
  return encode_container(field, options, "cannot store the compressed field").layout;
}

CompressedField read_container(const fs::path& path, ContainerOptions* stored_options) {
  const std::string bytes = read_container_bytes(path);
  const ContainerLayout layout = parse_layout(bytes, path);
  return ContainerDecoder(bytes, layout, path).decode(stored_options);
}

ContainerLayout describe_container(const fs::path& path) {
  return parse_layout(read_container_bytes(path), path);
}

CompressedField quantize_for_container(const CompressedField& field,
                                       const ContainerOptions& options) {
  const std::string where = "cannot store the compressed field";
  CompressedField quantized = field;
  if (options.weights == ValuePrecision::float16)
    for (Eigen::Index i = 0; i < quantized.weights.size(); ++i) {
      float& w = quantized.weights.data()[i];
      w = half_bits_to_float(checked_half(
          w, [&] { return weight_text(std::size_t(i), field.terms); }, where));
    }
  if (options.residual == ValuePrecision::float16)
    for (std::size_t k = 0; k < quantized.residual.values.size(); ++k) {
      float& v = quantized.residual.values[k];
      v = half_bits_to_float(checked_half(
          v, [&] { return residual_entry_text(field.residual, k); }, where));
    }
  return quantized;
}

RelativeError quantization_error(const CompressedField& field, const ContainerOptions& options) {
  return relative_error(field, quantize_for_container(field, options));
}

}  // namespace relume
