// How a section of a version-2 container is stored: its raw bytes, or zstd-compressed after a
// reversible filter that helps numbers compress: a byte shuffle (all first bytes of the
// elements, then all second bytes, ...) or a delta of consecutive elements before the shuffle
// (for ids and counts that change little from one stored row to the next). The writer tries
// each and keeps the smallest; the section table records the choice.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace relume {

// zstd's level for every section: within a few percent of level 19 on containers, several times
// faster (docs/container.md).
inline constexpr int section_zstd_level = 12;

enum class SectionFilter : std::uint8_t { none = 0, shuffle = 1, delta_shuffle = 2 };

struct SectionCoding {
  bool zstd = false;
  SectionFilter filter = SectionFilter::none;
  int element_bytes = 1;  // 1, 2, 4 or 8: the size of the numbers the filter works on

  // The section table's 32-bit coding word: bits 0-7 codec (0 raw, 1 zstd), 8-15 filter,
  // 16-23 element bytes.
  std::uint32_t word() const;
  // Throws Error("<where>: ...") for an unknown codec, filter or element size.
  static SectionCoding from_word(std::uint32_t word, const std::string& where);
  std::string describe() const;  // "raw", "zstd", "zstd+shuffle4", "zstd+delta2"
};

struct CodedSection {
  std::string bytes;
  SectionCoding coding;
};

// `raw` (numbers of `element_bytes` bytes) after `filter`: the bytes a codec then compresses.
std::string filtered_bytes(const std::string& raw, SectionFilter filter, int element_bytes);

// The filters a section of `element_bytes`-byte numbers is tried with, in order (of equal sizes
// the first wins): none, shuffle (numbers of several bytes), delta then shuffle.
std::vector<SectionFilter> candidate_filters(int element_bytes);

// The smallest of: raw, and zstd after each filter, for numbers of `element_bytes` bytes
// (raw.size() must be a multiple of it).
CodedSection code_section(const std::string& raw, int element_bytes);

// Throws Error("<where>: ...") when `coded_bytes` of a section of `coding` cannot decode to
// `raw_bytes` (stored raw: they must be equal; zstd: at most 32768 times as many), so that a
// table's claimed sizes are bounded by the file's real size before anything is allocated.
void check_coded_size(std::uint64_t coded_bytes, std::uint64_t raw_bytes,
                      const SectionCoding& coding, const std::string& where);

// The raw bytes of a coded section, which must be exactly `raw_bytes` long (the caller bounds
// raw_bytes before this allocates it). Throws Error("<where>: ...") for a damaged zstd frame or
// a size other than raw_bytes.
std::string decode_section(std::string_view coded, const SectionCoding& coding,
                           std::uint64_t raw_bytes, const std::string& where);

}  // namespace relume
