// What the fuzz targets share: the rule that a reader may refuse an input only with a
// relume::Error (anything else escaping is a finding, reported by libFuzzer as a crash), a
// scratch file or folder in memory-backed storage for readers that take a path, and the repair of
// a mutated container's checksums.
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

// Recomputes every section's CRC-32 over the bytes its table entry points at, then the table's,
// for every format version (40-byte entries in version 1, 48 from 2), so that a mutated section
// passes the frame check and reaches its decoder. Leaves bytes without a whole table alone.
void repair_container_checksums(std::string& bytes);

}  // namespace relume::fuzz
