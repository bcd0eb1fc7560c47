// Implementation of the bitmap / run-length position sets (see container_bit_set.hpp).
#include "container_bit_set.hpp"

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

void check_count(ByteReader& reader, std::uint64_t count, std::uint64_t max_positions) {
  if (count > max_positions)
    reader.fail("holds more than the " + std::to_string(max_positions) + " positions expected");
}

std::vector<std::uint64_t> decode_bitmap(ByteReader& reader, std::uint64_t universe,
                                         std::uint64_t max_positions) {
  const std::uint64_t byte_count = (universe + 7) / 8;
  if (reader.remaining() != byte_count)
    reader.fail("the bitmap has " + std::to_string(reader.remaining()) + " bytes, expected " +
                std::to_string(byte_count) + " for " + std::to_string(universe) + " bits");
  std::vector<std::uint64_t> positions;
  for (std::uint64_t b = 0; b < byte_count; ++b) {
    const std::uint8_t byte = reader.u8();
    for (int bit = 0; bit < 8; ++bit) {
      if (!(byte & (1u << bit))) continue;
      const std::uint64_t q = b * 8 + bit;
      if (q >= universe)
        reader.fail("bit " + std::to_string(q) + " is set beyond the " + std::to_string(universe) +
                    " bits of the bitmap");
      check_count(reader, positions.size() + 1, max_positions);
      positions.push_back(q);
    }
  }
  return positions;
}

std::vector<std::uint64_t> decode_runs(ByteReader& reader, std::uint64_t universe,
                                       std::uint64_t max_positions) {
  std::vector<std::uint64_t> positions;
  std::uint64_t covered = 0;
  bool present = false;
  bool first = true;
  while (reader.remaining() > 0) {
    const std::uint64_t length = reader.varint();
    if (length == 0 && !first) reader.fail("a run after the first has length 0");
    if (length > universe - covered)
      reader.fail("the runs cover more than the " + std::to_string(universe) + " positions");
    if (present) {
      check_count(reader, positions.size() + length, max_positions);
      for (std::uint64_t q = covered; q < covered + length; ++q) positions.push_back(q);
    }
    covered += length;
    present = !present;
    first = false;
  }
  if (covered != universe)
    reader.fail("the runs cover " + std::to_string(covered) + " positions, expected " +
                std::to_string(universe));
  return positions;
}

}  // namespace

std::string encode_bit_set(const std::vector<std::uint64_t>& positions, std::uint64_t universe) {
  std::string runs = encode_runs(positions, universe);
  if (runs.size() < 1 + (universe + 7) / 8) return runs;
  return encode_bitmap(positions, universe);
}

std::vector<std::uint64_t> decode_bit_set(ByteReader& reader, std::uint64_t universe,
                                          std::uint64_t max_positions) {
  const std::uint8_t encoding = reader.u8();
  switch (encoding) {
    case static_cast<std::uint8_t>(BitSetEncoding::bitmap):
      return decode_bitmap(reader, universe, max_positions);
    case static_cast<std::uint8_t>(BitSetEncoding::runs):
      return decode_runs(reader, universe, max_positions);
  }
  reader.fail("unknown set encoding " + std::to_string(encoding) +
              " (expected 0 = bitmap or 1 = runs)");
}

}  // namespace relume
