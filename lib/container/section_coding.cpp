// Implementation of the container's section coding: filters and zstd.
#include "container/section_coding.hpp"

#include <zstd.h>

#include <limits>
#include <memory>
#include <optional>
#include <relume/error.hpp>
#include <string_view>
#include <vector>

namespace relume {
namespace {

std::string shuffle(const std::string& raw, int element_bytes) {
  const std::size_t count = raw.size() / std::size_t(element_bytes);
  std::string out(raw.size(), '\0');
  for (std::size_t i = 0; i < count; ++i)
    for (int b = 0; b < element_bytes; ++b)
      out[std::size_t(b) * count + i] = raw[i * std::size_t(element_bytes) + std::size_t(b)];
  return out;
}

std::string unshuffle(const std::string& shuffled, int element_bytes) {
  const std::size_t count = shuffled.size() / std::size_t(element_bytes);
  std::string out(shuffled.size(), '\0');
  for (std::size_t i = 0; i < count; ++i)
    for (int b = 0; b < element_bytes; ++b)
      out[i * std::size_t(element_bytes) + std::size_t(b)] = shuffled[std::size_t(b) * count + i];
  return out;
}

std::uint64_t element(const std::string& bytes, std::size_t i, int element_bytes) {
  std::uint64_t value = 0;
  for (int b = element_bytes - 1; b >= 0; --b)
    value = (value << 8) |
            static_cast<unsigned char>(bytes[i * std::size_t(element_bytes) + std::size_t(b)]);
  return value;
}

void set_element(std::string& bytes, std::size_t i, int element_bytes, std::uint64_t value) {
  for (int b = 0; b < element_bytes; ++b, value >>= 8)
    bytes[i * std::size_t(element_bytes) + std::size_t(b)] = static_cast<char>(value & 0xFF);
}

// x[i] - x[i-1] modulo 2^(8 element_bytes), shuffled (as shuffle does) in the same pass, so that
// a large section is copied once; undelta is the inverse of the delta.
std::string delta_shuffle(const std::string& raw, int element_bytes) {
  const std::size_t count = raw.size() / std::size_t(element_bytes);
  std::string out(raw.size(), '\0');
  std::uint64_t previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t value = element(raw, i, element_bytes);
    std::uint64_t difference = i == 0 ? value : value - previous;
    previous = value;
    for (int b = 0; b < element_bytes; ++b, difference >>= 8)
      out[std::size_t(b) * count + i] = static_cast<char>(difference & 0xFF);
  }
  return out;
}

std::string undelta(const std::string& deltas, int element_bytes) {
  std::string out = deltas;
  const std::size_t count = deltas.size() / std::size_t(element_bytes);
  for (std::size_t i = 1; i < count; ++i)
    set_element(out, i, element_bytes,
                element(out, i - 1, element_bytes) + element(deltas, i, element_bytes));
  return out;
}

// The output buffer is left uninitialized: zstd touches only the pages it writes, so a section
// costs its compressed size in memory, not its worst-case bound.
std::string zstd_compress(std::string_view raw) {
  const std::size_t bound = ZSTD_compressBound(raw.size());
  const std::unique_ptr<char[]> out(new char[bound]);
  ZSTD_CCtx* context = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, section_zstd_level);
  ZSTD_CCtx_setParameter(context, ZSTD_c_checksumFlag, 1);
  const std::size_t size = ZSTD_compress2(context, out.get(), bound, raw.data(), raw.size());
  ZSTD_freeCCtx(context);
  if (ZSTD_isError(size))
    throw Error(std::string("zstd cannot compress: ") + ZSTD_getErrorName(size));
  return std::string(out.get(), size);
}

bool valid_element_bytes(int bytes) { return bytes == 1 || bytes == 2 || bytes == 4 || bytes == 8; }

}  // namespace

std::string filtered_bytes(const std::string& raw, SectionFilter filter, int element_bytes) {
  switch (filter) {
    case SectionFilter::none:
      break;
    case SectionFilter::shuffle:
      return shuffle(raw, element_bytes);
    case SectionFilter::delta_shuffle:
      return delta_shuffle(raw, element_bytes);
  }
  return raw;
}

std::uint32_t SectionCoding::word() const {
  return std::uint32_t(zstd ? 1 : 0) | (std::uint32_t(filter) << 8) |
         (std::uint32_t(element_bytes) << 16);
}

SectionCoding SectionCoding::from_word(std::uint32_t word, const std::string& where) {
  SectionCoding coding;
  const std::uint32_t codec = word & 0xFF, filter = (word >> 8) & 0xFF;
  coding.element_bytes = int((word >> 16) & 0xFF);
  if (codec > 1 || filter > 2 || !valid_element_bytes(coding.element_bytes) || (word >> 24) != 0 ||
      (codec == 0 && filter != 0))
    throw Error(where + ": unknown coding word 0x" + [&] {
      char text[16];
      std::snprintf(text, sizeof text, "%08X", word);
      return std::string(text);
    }() + " in the section table (expected raw or zstd with a shuffle or delta filter)");
  coding.zstd = codec == 1;
  coding.filter = SectionFilter(filter);
  return coding;
}

std::string SectionCoding::describe() const {
  if (!zstd) return "raw";
  const std::string size = std::to_string(element_bytes);
  switch (filter) {
    case SectionFilter::none:
      return "zstd";
    case SectionFilter::shuffle:
      return "zstd+shuffle" + size;
    case SectionFilter::delta_shuffle:
      return "zstd+delta" + size;
  }
  return "zstd";
}

std::vector<SectionFilter> candidate_filters(int element_bytes) {
  std::vector<SectionFilter> filters{SectionFilter::none};
  if (element_bytes > 1) filters.push_back(SectionFilter::shuffle);
  filters.push_back(SectionFilter::delta_shuffle);
  return filters;
}

CodedSection code_section(const std::string& raw, int element_bytes) {
  if (!valid_element_bytes(element_bytes) || raw.size() % std::size_t(element_bytes) != 0)
    throw Error("internal: a section of " + std::to_string(raw.size()) + " bytes is not made of " +
                std::to_string(element_bytes) + "-byte numbers");
  // The smallest coding, raw if none is smaller; raw is copied only then.
  std::optional<CodedSection> best;
  for (SectionFilter filter : candidate_filters(element_bytes)) {
    std::string coded = filter == SectionFilter::none
                            ? zstd_compress(raw)
                            : zstd_compress(filtered_bytes(raw, filter, element_bytes));
    if (coded.size() < (best ? best->bytes.size() : raw.size()))
      best = CodedSection{std::move(coded), {true, filter, element_bytes}};
  }
  return best ? std::move(*best) : CodedSection{raw, {}};
}

void check_coded_size(std::uint64_t coded_bytes, std::uint64_t raw_bytes,
                      const SectionCoding& coding, const std::string& where) {
  if (!coding.zstd) {
    if (coded_bytes != raw_bytes)
      throw Error(where + " is stored raw in " + std::to_string(coded_bytes) +
                  " bytes, but the section table says it decodes to " + std::to_string(raw_bytes));
    return;
  }
  // A zstd block of at most 128 KiB takes at least 4 coded bytes (a 3-byte header and one byte
  // of an RLE block), so no valid frame decodes to more than 32768 times its size.
  // A coded size of 2^49 or more (the product would wrap) may decode to any size: whether the
  // file holds that many bytes is the section table's next check.
  constexpr std::uint64_t max_zstd_ratio = (128u << 10) / 4;
  const bool product_fits =
      coded_bytes <= std::numeric_limits<std::uint64_t>::max() / max_zstd_ratio;
  if (product_fits && raw_bytes > coded_bytes * max_zstd_ratio)
    throw Error(where + ": " + std::to_string(coded_bytes) + " zstd-coded bytes cannot decode to " +
                std::to_string(raw_bytes) + " bytes as the section table says (at most " +
                std::to_string(max_zstd_ratio) + " times as many): the section is corrupt");
}

std::string decode_section(std::string_view coded, const SectionCoding& coding,
                           std::uint64_t raw_bytes, const std::string& where) {
  check_coded_size(coded.size(), raw_bytes, coding, where);
  if (!coding.zstd) return std::string(coded);
  const unsigned long long content = ZSTD_getFrameContentSize(coded.data(), coded.size());
  if (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN)
    throw Error(where + ": is not a complete zstd frame (corrupt or truncated)");
  if (content != raw_bytes)
    throw Error(where + ": decompresses to " + std::to_string(content) +
                " bytes, the section table says " + std::to_string(raw_bytes));
  if (raw_bytes % std::uint64_t(coding.element_bytes) != 0)
    throw Error(where + ": " + std::to_string(raw_bytes) + " bytes are not made of " +
                std::to_string(coding.element_bytes) + "-byte numbers");
  std::string raw(raw_bytes, '\0');
  const std::size_t size = ZSTD_decompress(raw.data(), raw.size(), coded.data(), coded.size());
  if (ZSTD_isError(size) || size != raw_bytes)
    throw Error(where + ": zstd cannot decompress it (" +
                (ZSTD_isError(size) ? std::string(ZSTD_getErrorName(size)) : "short") +
                "): the section is corrupt");
  switch (coding.filter) {
    case SectionFilter::none:
      return raw;
    case SectionFilter::shuffle:
      return unshuffle(raw, coding.element_bytes);
    case SectionFilter::delta_shuffle:
      return undelta(unshuffle(raw, coding.element_bytes), coding.element_bytes);
  }
  return raw;
}

}  // namespace relume
