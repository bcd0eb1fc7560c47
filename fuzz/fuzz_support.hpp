// What the fuzz targets share: the rule that a reader may refuse an input only with a
// relume::Error (anything else escaping is a finding, reported by libFuzzer as a crash), and a
// scratch file or folder in memory-backed storage for readers that take a path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace relume::fuzz {

// Runs `read`; a relume::Error is an accepted refusal, any other exception aborts.
void expect_only_relume_errors(const std::function<void()>& read);

// A folder of this process under /dev/shm (else the temp folder), made once.
const std::filesystem::path& scratch_folder();

// Writes `size` bytes to scratch_folder() / name and returns the path.
std::filesystem::path write_scratch_file(const std::string& name, const std::uint8_t* data,
                                         std::size_t size);

}  // namespace relume::fuzz
