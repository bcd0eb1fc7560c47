// Implementation of the bitmap / run-length position sets (see container_bit_set.hpp).
#include "container/container_bit_set.hpp"

#include <algorithm>

namespace relume {
namespace {

std::string encode_bitmap(const std::vector<std::uint64_t>& positions, std::uint64_t universe) {
  std::string bytes(1 + (universe + 7) / 8, '\0');
  bytes[0] = static_cast<char>(BitSetEncoding::bitmap);
  for (std::uint64_t q : positions) bytes[1 + q / 8] |= static_cast<char>(1u << (q % 8));
  return bytes;
}

std::string encode_runs(const std::vector<std::uint64_t>& positions, std::uint64_t universe) {
  ByteWriter writer;
  writer.u8(static_cast<std::uint8_t>(BitSetEncoding::runs));
  std::uint64_t next = 0;  // first position not yet covered by a run
  std::size_t i = 0;
  while (i < positions.size()) {
    const std::uint64_t start = positions[i];
    std::size_t j = i + 1;
    while (j < positions.size() && positions[j] == positions[j - 1] + 1) ++j;
    writer.varint(start - next);  // absent run
    writer.varint(j - i);         // present run
    next = start + (j - i);
    i = j;
  }
  if (next < universe) writer.varint(universe - next);
  return writer.take();
}

// A present run of positions [start, start + length).
struct PresentRun {
  std::uint64_t start;
  std::uint64_t length;
};

// The present runs of a bitmap (one run per set bit, merged with its predecessor when adjacent).
std::vector<PresentRun> bitmap_runs(ByteReader& reader, std::uint64_t universe) {
  const std::uint64_t byte_count = (universe + 7) / 8;
  if (reader.remaining() != byte_count)
    reader.fail("the bitmap has " + std::to_string(reader.remaining()) + " bytes, expected " +
                std::to_string(byte_count) + " for " + std::to_string(universe) + " bits");
  std::vector<PresentRun> runs;
  for (std::uint64_t b = 0; b < byte_count; ++b) {
    const std::uint8_t byte = reader.u8();
    for (int bit = 0; bit < 8; ++bit) {
      if (!(byte & (1u << bit))) continue;
      const std::uint64_t q = b * 8 + bit;
      if (q >= universe)
        reader.fail("bit " + std::to_string(q) + " is set beyond the " + std::to_string(universe) +
                    " bits of the bitmap");
      if (!runs.empty() && runs.back().start + runs.back().length == q)
        ++runs.back().length;
      else
        runs.push_back({q, 1});
    }
  }
  return runs;
}

// The present runs of a run-length set; their number is bounded by the section's bytes.
std::vector<PresentRun> length_runs(ByteReader& reader, std::uint64_t universe) {
  std::vector<PresentRun> runs;
  std::uint64_t covered = 0;
  bool present = false;
  bool first = true;
  while (reader.remaining() > 0) {
    const std::uint64_t length = reader.varint();
    if (length == 0 && !first) reader.fail("a run after the first has length 0");
    if (length > universe - covered)
      reader.fail("the runs cover more than the " + std::to_string(universe) + " positions");
    if (present) runs.push_back({covered, length});
    covered += length;
    present = !present;
    first = false;
  }
  if (covered != universe)
    reader.fail("the runs cover " + std::to_string(covered) + " positions, expected " +
                std::to_string(universe));
  return runs;
}

// Every present run of the set, validated, before anything of the universe's size is allocated.
std::vector<PresentRun> present_runs(ByteReader& reader, std::uint64_t universe) {
  const std::uint8_t encoding = reader.u8();
  switch (encoding) {
    case static_cast<std::uint8_t>(BitSetEncoding::bitmap):
      return bitmap_runs(reader, universe);
    case static_cast<std::uint8_t>(BitSetEncoding::runs):
      return length_runs(reader, universe);
  }
  reader.fail("unknown set encoding " + std::to_string(encoding) +
              " (expected 0 = bitmap or 1 = runs)");
}

}  // namespace

std::string encode_bit_set(const std::vector<std::uint64_t>& positions, std::uint64_t universe) {
  std::string runs = encode_runs(positions, universe);
  if (runs.size() < 1 + (universe + 7) / 8) return runs;
  return encode_bitmap(positions, universe);
}

std::vector<std::uint64_t> decode_bit_set(ByteReader& reader, std::uint64_t universe,
                                          std::uint64_t max_positions) {
  const std::vector<PresentRun> runs = present_runs(reader, universe);
  std::uint64_t count = 0;
  for (const PresentRun& run : runs) count += run.length;
  if (count > max_positions)
    reader.fail("holds " + std::to_string(count) + " positions, more than the " +
                std::to_string(max_positions) + " expected");
  std::vector<std::uint64_t> positions;
  positions.reserve(count);
  for (const PresentRun& run : runs)
    for (std::uint64_t q = run.start; q < run.start + run.length; ++q) positions.push_back(q);
  return positions;
}

std::vector<std::uint8_t> decode_bit_mask(ByteReader& reader, std::uint64_t universe) {
  const std::vector<PresentRun> runs = present_runs(reader, universe);
  std::vector<std::uint8_t> mask(universe, 0);
  for (const PresentRun& run : runs)
    std::fill_n(mask.begin() + std::ptrdiff_t(run.start), run.length, std::uint8_t(1));
  return mask;
}

}  // namespace relume
