// Implementation of the fuzz targets' shared helpers.
#include "fuzz_support.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <relume/error.hpp>

#include "core/crc32.hpp"
#include "core/memory_budget.hpp"

namespace relume::fuzz {
namespace fs = std::filesystem;

namespace {

// Readers refuse inputs whose decoding would need more than this (core/memory_budget.hpp), as
// they would on a machine with this much memory; libFuzzer's -malloc_limit_mb catches any
// allocation that skipped the check.
[[maybe_unused]] const bool memory_limited = [] {
  set_memory_limit(std::uint64_t(256) << 20);
  return true;
}();

std::uint64_t load(const std::string& bytes, std::size_t at, int width) {
  std::uint64_t value = 0;
  for (int b = 0; b < width; ++b)
    value |= std::uint64_t(static_cast<unsigned char>(bytes[at + b])) << (8 * b);
  return value;
}

void store32(std::string& bytes, std::size_t at, std::uint32_t value) {
  for (int b = 0; b < 4; ++b) bytes[at + b] = static_cast<char>((value >> (8 * b)) & 0xFF);
}

}  // namespace

void repair_container_checksums(std::string& bytes) {
  constexpr std::size_t table_start = 16;  // magic, version, section count
  if (bytes.size() < table_start) return;
  // Versions 3 and 4 were left unrepaired once, so mutations of the newest containers stopped at
  // the frame check.
  const std::uint64_t version = load(bytes, 8, 4), count = load(bytes, 12, 4);
  if (version < 1 || version > 16 || count > 64) return;
  const std::size_t entry = version == 1 ? 40 : 48;
  const std::size_t crc_at = entry - 8;  // within an entry
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

void expect_only_relume_errors(const std::function<void()>& read) {
  try {
    read();
  } catch (const relume::Error&) {
    // A refusal with a message: what a reader must do with bad input.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: a reader threw a non-relume exception: %s\n", e.what());
    std::abort();
  }
}

const fs::path& scratch_folder() {
  static const fs::path folder = [] {
    const fs::path base =
        fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path path = base / ("relume-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(path);
    return path;
  }();
  return folder;
}

fs::path write_scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const fs::path path = scratch_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

}  // namespace relume::fuzz
