// Compact storage of a set of positions in [0, universe) for the container's mask and functions
// sections. One leading byte says how the rest is stored, whichever is smaller (bitmap on ties):
//   0 = bitmap: ceil(universe / 8) bytes, position q is bit (q % 8) of byte q / 8, unused high
//       bits of the last byte are zero;
//   1 = runs: LEB128 varints, the lengths of alternating runs of absent and present positions,
//       starting with an absent run (which may be 0); the runs add up to universe exactly and
//       every run after the first is positive.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "container/container_bytes.hpp"

namespace relume {

enum class BitSetEncoding : std::uint8_t { bitmap = 0, runs = 1 };

// `positions` ascending, each < universe.
std::string encode_bit_set(const std::vector<std::uint64_t>& positions, std::uint64_t universe);

// Reads the whole of `reader`'s data; throws through reader.fail on anything malformed or on more
// than `max_positions` present positions (checked before they are stored).
std::vector<std::uint64_t> decode_bit_set(ByteReader& reader, std::uint64_t universe,
                                          std::uint64_t max_positions);

// The same set as one byte per position (1 = present); the section is validated in full before
// the universe-sized mask is allocated.
std::vector<std::uint8_t> decode_bit_mask(ByteReader& reader, std::uint64_t universe);

}  // namespace relume
