// Implementation of the fuzz targets' shared helpers.
#include "fuzz_support.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <relume/error.hpp>

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

}  // namespace

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
