// Fuzz target: the section coding of containers (container/section_coding.hpp), both ways. The
// input's first 4 bytes are a coding word and the next 4 a raw size, as a section table gives
// them, and the rest is the stored section: it must decode to exactly that size or be refused
// with a relume::Error. The rest, as raw numbers of the word's element size, must also come back
// unchanged from code_section and decode_section (the writer's choice of raw, zstd and filters).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "container/section_coding.hpp"
#include "fuzz_support.hpp"

namespace {

std::uint32_t load32(const std::uint8_t* bytes) {
  return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
         std::uint32_t(bytes[3]) << 24;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 8) return 0;
  const std::uint32_t word = load32(data);
  // At most 4 MiB claimed: the container decoder bounds a claim by the memory budget first.
  const std::uint64_t raw_bytes = load32(data + 4) % (std::uint64_t(4) << 20);
  const std::string stored(reinterpret_cast<const char*>(data + 8), size - 8);
  relume::fuzz::expect_only_relume_errors([&] {
    const relume::SectionCoding coding = relume::SectionCoding::from_word(word, "fuzz");
    relume::check_coded_size(stored.size(), raw_bytes, coding, "fuzz");
    if (relume::decode_section(stored, coding, raw_bytes, "fuzz").size() != raw_bytes) std::abort();
  });

  const int element_bytes = 1 << (data[2] % 4);
  const std::string raw = stored.substr(0, stored.size() / element_bytes * element_bytes);
  const relume::CodedSection coded = relume::code_section(raw, element_bytes);
  if (relume::decode_section(coded.bytes, coded.coding, raw.size(), "round trip") != raw)
    std::abort();
  return 0;
}
