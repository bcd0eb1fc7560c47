// Implementation of the container's outer frame: the section table of versions 1 and 2.
#include "container/container_format.hpp"

#include <algorithm>
#include <cstdio>
#include <relume/error.hpp>

#include "container/container_bytes.hpp"
#include "core/crc32.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace {

constexpr std::string_view container_magic{"RELUME\0\0", 8};
constexpr std::size_t section_name_bytes = 16;
constexpr std::size_t fixed_preamble_bytes =
    container_magic.size() + 4 + 4;  // magic, version, count

std::size_t entry_bytes(std::uint32_t version) { return version == 1 ? 40 : 48; }

std::uint64_t preamble_bytes(std::uint32_t version) {
  return fixed_preamble_bytes + container_section_names(version).size() * entry_bytes(version) + 4;
}

std::string hex32(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

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

// Checks the fixed part of the preamble; returns the version.
std::uint32_t check_magic_and_version(const std::string& bytes, const std::string& file) {
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
  ByteReader in(std::string_view(bytes).substr(container_magic.size()), file + ": preamble");
  const std::uint32_t version = in.u32();
  if (version < 1 || version > container_format_version)
    throw Error(file + ": container format version " + std::to_string(version) +
                " is not supported (this relume reads versions 1 to " +
                std::to_string(container_format_version) + ")");
  const std::uint32_t count = in.u32();
  const std::size_t expected = container_section_names(version).size();
  if (count != expected)
    throw Error(file + ": the section table is corrupt: it lists " + std::to_string(count) +
                " sections, format version " + std::to_string(version) + " has " +
                std::to_string(expected));
  if (bytes.size() < preamble_bytes(version))
    throw Error(file + " is truncated: the section table needs " +
                std::to_string(preamble_bytes(version)) + " bytes, the file has " +
                std::to_string(bytes.size()));
  return version;
}

}  // namespace

const std::vector<std::string_view>& container_section_names(std::uint32_t version) {
  static const std::vector<std::string_view> version1{
      "header",           "lights",         "mask",    "functions",
      "clusters",         "bases",          "weights", "residual_offsets",
      "residual_indices", "residual_values"};
  static const std::vector<std::string_view> version2{
      "header",         "lights",           "mask",
      "functions",      "dark_pixels",      "dark",
      "clusters",       "basis_scales",     "bases",
      "weights",        "residual_offsets", "residual_indices",
      "residual_values"};
  static const std::vector<std::string_view> version4{
      "header",           "lights",         "mask",       "functions",
      "dark_pixels",      "dark",           "dark_gains", "clusters",
      "basis_scales",     "bases",          "weights",    "residual_offsets",
      "residual_indices", "residual_values"};
  static const std::vector<std::string_view> version5{
      "header",           "lights",         "mask",       "functions",     "dark_pixels",
      "dark",             "dark_gains",     "clusters",   "basis_scales",  "bases",
      "weights",          "weight_planes",  "residual_offsets", "residual_indices",
      "residual_values"};
  static const std::vector<std::string_view> version6{
      "header",         "lights",        "mask",          "functions",        "dark_pixels",
      "dark",           "dark_gains",    "clusters",      "basis_scales",     "bases",
      "weights",        "weight_planes", "weight_colour", "residual_offsets", "residual_indices",
      "residual_values"};
  // Version 3 has version 2's sections.
  return version == 1   ? version1
         : version < 4  ? version2
         : version == 4 ? version4
         : version == 5 ? version5
                        : version6;
}

std::string encode_preamble(const ContainerLayout& layout,
                            const std::vector<SectionCoding>& codings) {
  ByteWriter file;
  file.bytes(container_magic);
  file.u32(layout.version);
  file.u32(static_cast<std::uint32_t>(layout.sections.size()));
  for (std::size_t s = 0; s < layout.sections.size(); ++s) {
    std::string name = layout.sections[s].name;
    name.resize(section_name_bytes, '\0');
    file.bytes(name);
    file.u64(layout.sections[s].offset);
    file.u64(layout.sections[s].bytes);
    file.u64(layout.sections[s].raw_bytes);
    file.u32(layout.sections[s].crc32);
    file.u32(codings[s].word());
  }
  file.u32(crc32(file.data()));
  return file.take();
}

ContainerLayout new_container_layout() {
  ContainerLayout layout;
  layout.version = container_format_version;
  layout.preamble_bytes = preamble_bytes(layout.version);
  layout.file_bytes = layout.preamble_bytes;
  return layout;
}

std::string assemble_container(std::vector<StoredSection> sections, bool entropy_coding,
                               unsigned threads, ContainerLayout* layout_out) {
  ContainerLayout layout = new_container_layout();
  std::vector<std::size_t> raw_bytes;
  for (const StoredSection& section : sections) raw_bytes.push_back(section.raw.size());
  std::vector<CodedSection> coded(sections.size());
  parallel_for(sections.size(), threads, [&](std::size_t s, unsigned) {
    StoredSection& section = sections[s];
    coded[s] = entropy_coding && section.name != "header"
                   ? code_section(section.raw, section.element_bytes)
                   : CodedSection{std::move(section.raw), {}};
    std::string().swap(section.raw);  // frees it (assigning an empty string may keep the buffer)
  });
  std::vector<SectionCoding> codings;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const CodedSection& c = coded[s];
    codings.push_back(c.coding);
    layout.sections.push_back({std::string(sections[s].name), layout.file_bytes, c.bytes.size(),
                               raw_bytes[s], crc32(c.bytes), c.coding.describe()});
    layout.file_bytes += c.bytes.size();
  }
  std::string file = encode_preamble(layout, codings);
  for (const CodedSection& c : coded) file += c.bytes;
  if (layout_out) *layout_out = std::move(layout);
  return file;
}

ParsedContainer parse_container(const std::string& bytes, const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::uint32_t version = check_magic_and_version(bytes, file);
  const std::vector<std::string_view>& names = container_section_names(version);
  ParsedContainer parsed;
  ContainerLayout& layout = parsed.layout;
  layout.version = version;
  layout.preamble_bytes = preamble_bytes(version);
  layout.file_bytes = bytes.size();
  ByteReader table(std::string_view(bytes).substr(fixed_preamble_bytes), file + ": section table");
  std::vector<std::uint32_t> words;
  for (std::size_t s = 0; s < names.size(); ++s) {
    ContainerSection section;
    const std::string_view name = table.bytes(section_name_bytes);
    section.name = std::string(name.substr(0, name.find('\0')));
    section.offset = table.u64();
    section.bytes = table.u64();
    section.raw_bytes = version == 1 ? section.bytes : table.u64();
    section.crc32 = table.u32();
    words.push_back(table.u32());  // version 1: reserved, 0
    layout.sections.push_back(section);
  }
  const std::uint32_t stored_table_crc = table.u32();
  const std::uint32_t computed_table_crc = crc32(bytes.data(), layout.preamble_bytes - 4);
  if (stored_table_crc != computed_table_crc)
    throw Error(file + ": the section table is corrupt (CRC-32 " + hex32(computed_table_crc) +
                ", the file says " + hex32(stored_table_crc) + ")");

  std::uint64_t expected_offset = layout.preamble_bytes;
  for (std::size_t s = 0; s < names.size(); ++s) {
    ContainerSection& section = layout.sections[s];
    if (section.name != names[s])
      throw Error(file + ": section " + std::to_string(s) + " is named '" + section.name +
                  "', expected '" + std::string(names[s]) + "'");
    const std::string where = file + ": section '" + section.name + "'";
    if (version == 1) {
      if (words[s] != 0)
        throw Error(where + " has reserved field " + hex32(words[s]) +
                    " in the section table, expected 0");
      parsed.codings.push_back({});
    } else {
      const SectionCoding coding = SectionCoding::from_word(words[s], where);
      parsed.codings.push_back(coding);
      section.coding = coding.describe();
      check_coded_size(section.bytes, section.raw_bytes, coding, where);
    }
    if (section.offset != expected_offset)
      throw Error(where + " starts at byte " + std::to_string(section.offset) + ", expected " +
                  std::to_string(expected_offset));
    if (section.bytes > bytes.size() || section.offset > bytes.size() - section.bytes)
      throw Error(file + " is truncated: section '" + section.name + "' needs bytes " +
                  std::to_string(section.offset) + " to " +
                  std::to_string(section.offset + section.bytes) + ", the file has " +
                  std::to_string(bytes.size()));
    const std::uint32_t computed = crc32(bytes.data() + section.offset, section.bytes);
    if (computed != section.crc32)
      throw Error(where + " is corrupt (CRC-32 " + hex32(computed) + ", the section table says " +
                  hex32(section.crc32) + ")");
    expected_offset = section.offset + section.bytes;
  }
  if (expected_offset != bytes.size())
    throw Error(file + " has " + std::to_string(bytes.size() - expected_offset) +
                " unexpected bytes after its last section");
  return parsed;
}

std::string ParsedContainer::contents(const std::string& bytes, std::string_view name,
                                      std::uint64_t raw_limit, const std::string& file) const {
  for (std::size_t s = 0; s < layout.sections.size(); ++s) {
    const ContainerSection& section = layout.sections[s];
    if (section.name != name) continue;
    const std::string where = file + ": section '" + section.name + "'";
    if (section.raw_bytes > raw_limit)
      throw Error(where + " decodes to " + std::to_string(section.raw_bytes) +
                  " bytes by the section table, more than the " + std::to_string(raw_limit) +
                  " its header allows");
    return decode_section(std::string_view(bytes).substr(section.offset, section.bytes), codings[s],
                          section.raw_bytes, where);
  }
  throw Error(file + ": the container has no section '" + std::string(name) + "'");
}

}  // namespace relume
