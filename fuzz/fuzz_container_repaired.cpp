// Fuzz target: the .relume container reader after the input's checksums are repaired (every
// section's CRC-32 recomputed over the bytes its table entry points at, then the table's), so
// that a mutated section passes the frame check and reaches its decoder: the header's JSON, the
// bit sets, zstd frames, the filters, the weight prediction and every consistency check.
#include <cstddef>
#include <cstdint>
#include <string>

#include "container/container.hpp"
#include "core/crc32.hpp"
#include "fuzz_support.hpp"

namespace {

std::uint64_t load(const std::string& bytes, std::size_t at, int width) {
  std::uint64_t value = 0;
  for (int b = 0; b < width; ++b)
    value |= std::uint64_t(static_cast<unsigned char>(bytes[at + b])) << (8 * b);
  return value;
}

void store32(std::string& bytes, std::size_t at, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) bytes[at + b] = static_cast<char>((value >> (8 * b)) & 0xFF);
}

// Recomputes the checksums of a version 1 (40-byte entries) or 2 (48-byte entries) table.
void repair_checksums(std::string& bytes) {
  constexpr std::size_t table_start = 16;  // magic, version, section count
  if (bytes.size() < table_start) return;
  const std::uint64_t version = load(bytes, 8, 4), count = load(bytes, 12, 4);
  if ((version != 1 && version != 2) || count > 64) return;
  const std::size_t entry = version == 1 ? 40 : 48;
  const std::size_t crc_at = version == 1 ? 32 : 40;  // within an entry
  const std::size_t table_end = table_start + count * entry;
  if (bytes.size() < table_end + 4) return;
  for (std::size_t s = 0; s < count; ++s) {
    const std::size_t at = table_start + s * entry;
    const std::uint64_t offset = load(bytes, at + 16, 8), length = load(bytes, at + 24, 8);
    if (offset <= bytes.size() && length <= bytes.size() - offset)
      store32(bytes, at + crc_at, relume::crc32(bytes.data() + offset, length));
  }
  store32(bytes, table_end, relume::crc32(bytes.data(), table_end));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  repair_checksums(bytes);
  relume::fuzz::expect_only_relume_errors([&] {
    relume::ContainerOptions stored;
    relume::decode_container(bytes, "fuzz.relume", &stored);
  });
  return 0;
}
