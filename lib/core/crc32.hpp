// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, the checksum of zlib and PNG), used to
// check every section of a .relume container and every chunk of a PNG before it is decoded.
// CRC-32 of "123456789" is 0xCBF43926.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace relume {

// Continues a running checksum: crc32(b, crc32(a)) == crc32(a + b). Start with previous = 0.
std::uint32_t crc32(const void* data, std::size_t bytes, std::uint32_t previous = 0);

inline std::uint32_t crc32(std::string_view bytes, std::uint32_t previous = 0) {
  return crc32(bytes.data(), bytes.size(), previous);
}

}  // namespace relume
