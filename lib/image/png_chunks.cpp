// Implementation of the PNG chunk check (see png_chunks.hpp).
#include "image/png_chunks.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <relume/error.hpp>
#include <string>
#include <vector>

#include "core/crc32.hpp"

namespace relume {
namespace {

constexpr std::array<unsigned char, 8> png_signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

std::uint32_t big_endian_32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 |
         std::uint32_t(bytes[2]) << 8 | std::uint32_t(bytes[3]);
}

// The type as it reads, bytes that are not letters in hex ("tE[00][00]").
std::string type_text(const unsigned char* type) {
  std::string text;
  for (int i = 0; i < 4; ++i) {
    if (std::isalpha(type[i])) {
      text += char(type[i]);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "[%02X]", type[i]);
      text += hex;
    }
  }
  return text;
}

}  // namespace

void check_png_chunks(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 8> signature{};
  if (!in.read(reinterpret_cast<char*>(signature.data()), signature.size()) ||
      signature != png_signature)
    return;
  const std::uint64_t size = std::filesystem::file_size(path);
  const auto corrupt = [&](const std::string& why) {
    return Error("cannot read image " + path.string() + ": a corrupt PNG: " + why);
  };
  std::vector<char> data(std::size_t(1) << 16);
  for (std::uint64_t offset = signature.size();;) {
    unsigned char header[8];  // length, type
    if (size - offset < 12 || !in.read(reinterpret_cast<char*>(header), sizeof header))
      throw corrupt("the file ends at byte " + std::to_string(size) +
                    " before its last chunk (IEND): it was cut short");
    const std::uint32_t length = big_endian_32(header);
    const std::string type = type_text(header + 4);
    const std::string chunk = "chunk '" + type + "' at byte " + std::to_string(offset);
    if (!std::isalpha(header[4]) || !std::isalpha(header[5]) || !std::isalpha(header[6]) ||
        !std::isalpha(header[7]))
      throw corrupt(chunk + " has no chunk type (four letters)");
    if (length > size - offset - 12)
      throw corrupt(chunk + " needs " + std::to_string(length) + " bytes of data, the file ends at byte " +
                    std::to_string(size) + ": it was cut short");
    std::uint32_t crc = crc32(header + 4, 4);
    for (std::uint32_t left = length; left > 0;) {
      const std::uint32_t step = std::min<std::uint32_t>(left, std::uint32_t(data.size()));
      in.read(data.data(), step);
      crc = crc32(data.data(), step, crc);
      left -= step;
    }
    unsigned char stored[4];
    in.read(reinterpret_cast<char*>(stored), sizeof stored);
    if (!in) throw corrupt("the file cannot be read past byte " + std::to_string(offset));
    if (big_endian_32(stored) != crc)
      throw corrupt(chunk + " does not match its CRC-32: its bytes were changed");
    offset += 12 + std::uint64_t(length);
    if (type == "IEND") return;
  }
}

}  // namespace relume
