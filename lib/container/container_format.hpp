// The container's outer format (docs/container.md): magic, version, section table with a CRC-32
// per section and of the table, then the sections back to back. Version 1 tables have 40-byte
// entries and raw sections; version 2 entries are 48 bytes and add each section's decoded size
// and its coding (lib/container/section_coding.hpp). This file assembles and parses that frame;
// what the sections mean is the encoder's and decoder's business.
#pragma once

#include <filesystem>
#include <relume/container.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "container/section_coding.hpp"

namespace relume {

// The sections of each format version, in file order.
const std::vector<std::string_view>& container_section_names(std::uint32_t version);

struct StoredSection {
  std::string_view name;
  std::string raw;        // decoded contents
  int element_bytes = 1;  // the size of the numbers it holds, for the coding filters
};

// The whole file in the current version: every section coded (code_section) unless
// `entropy_coding` is false or it is the header, `threads` sections at once; `layout`, when
// given, receives the table. Each section's raw bytes are let go once it is coded.
std::string assemble_container(std::vector<StoredSection> sections, bool entropy_coding,
                               unsigned threads, ContainerLayout* layout);

// An empty layout of the current version: its preamble's size, no sections yet (file_bytes is
// where the first section starts).
ContainerLayout new_container_layout();

// The preamble of a current-version file: magic, version, the table of `layout`'s sections (each
// coded as `codings` says) and its CRC-32. A writer that streams the sections writes this last,
// at offset 0.
std::string encode_preamble(const ContainerLayout& layout,
                            const std::vector<SectionCoding>& codings);

// A file whose frame has been checked: its table and how each section is coded.
struct ParsedContainer {
  ContainerLayout layout;
  std::vector<SectionCoding> codings;  // one per section, in file order

  // The decoded bytes of section `name`; `raw_limit` bounds the decoded size before anything is
  // allocated. Throws Error naming the file and section when the table claims more than the
  // limit or the coded bytes do not decode.
  std::string contents(const std::string& bytes, std::string_view name, std::uint64_t raw_limit,
                       const std::string& file) const;
};

// Checks magic, version, the section table and every checksum. Throws Error naming the file and
// the section at fault.
ParsedContainer parse_container(const std::string& bytes, const std::filesystem::path& path);

}  // namespace relume
