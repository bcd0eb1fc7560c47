// Writing stored (uncompressed) zip archives, following PKWARE's APPNOTE (sections 4.3.7 local
// file header, 4.3.12 central directory header, 4.3.16 end of central directory record).
#include "export/stored_zip.hpp"

#include <cstdint>
#include <limits>
#include <relume/error.hpp>
#include <set>

#include "core/crc32.hpp"

namespace relume {
namespace {

constexpr std::uint16_t dos_date_1980_01_01 = (0 << 9) | (1 << 5) | 1;
constexpr std::uint16_t version_needed = 10;  // 1.0: stored entries, no zip64

void put16(std::string& out, std::uint16_t v) {
  out += static_cast<char>(v & 0xff);
  out += static_cast<char>(v >> 8);
}

void put32(std::string& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((v >> shift) & 0xff);
}

std::uint32_t fit32(std::size_t value, const std::string& what) {
  if (value >= std::numeric_limits<std::uint32_t>::max())
    throw Error(what + " is " + std::to_string(value) +
                " bytes: a zip without zip64 holds under 4 GiB");
  return static_cast<std::uint32_t>(value);
}

// The fields local and central headers share, from "version needed" to the name length.
void put_common(std::string& out, std::uint32_t crc, std::uint32_t size, std::uint16_t name) {
  put16(out, version_needed);
  put16(out, 0);  // flags
  put16(out, 0);  // method: stored
  put16(out, 0);  // time 00:00:00
  put16(out, dos_date_1980_01_01);
  put32(out, crc);
  put32(out, size);  // compressed
  put32(out, size);  // uncompressed
  put16(out, name);
  put16(out, 0);  // extra field length
}

}  // namespace

std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
  if (entries.size() >= 0xffff)
    throw Error("a zip without zip64 holds fewer than 65535 entries, not " +
                std::to_string(entries.size()));
  std::string archive, directory;
  std::set<std::string> names;
  for (const auto& [name, contents] : entries) {
    if (name.empty() || name.size() >= 0xffff || !names.insert(name).second)
      throw Error("zip entry name '" + name + "' is empty, too long or given twice");
    const std::uint32_t size = fit32(contents.size(), "zip entry " + name);
    const std::uint32_t offset = fit32(archive.size(), "the zip before " + name);
    const std::uint32_t crc = crc32(contents);
    const auto name_length = static_cast<std::uint16_t>(name.size());

    put32(archive, 0x04034b50);
    put_common(archive, crc, size, name_length);
    archive += name;
    archive += contents;

    put32(directory, 0x02014b50);
    put16(directory, version_needed);  // version made by (MS-DOS attributes)
    put_common(directory, crc, size, name_length);
    put16(directory, 0);  // comment length
    put16(directory, 0);  // disk number
    put16(directory, 0);  // internal attributes
    put32(directory, 0);  // external attributes
    put32(directory, offset);
    directory += name;
  }
  const std::uint32_t directory_offset = fit32(archive.size(), "the zip's entries");
  const std::uint32_t directory_size = fit32(directory.size(), "the zip's central directory");
  fit32(archive.size() + directory.size(), "the zip");
  archive += directory;
  put32(archive, 0x06054b50);
  put16(archive, 0);  // this disk
  put16(archive, 0);  // disk of the central directory
  put16(archive, static_cast<std::uint16_t>(entries.size()));
  put16(archive, static_cast<std::uint16_t>(entries.size()));
  put32(archive, directory_size);
  put32(archive, directory_offset);
  put16(archive, 0);  // comment length
  return archive;
}

}  // namespace relume
