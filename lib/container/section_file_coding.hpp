// Section coding (container/section_coding.hpp) of a section too large for memory: its raw bytes
// are in a file and go through the filter and zstd a few megabytes at a time. The result is the
// coding code_section would choose for the same bytes (the smallest of raw and zstd after each
// filter), and the same decoded contents.
#pragma once

#include <cstdint>
#include <filesystem>

#include "container/section_coding.hpp"
#include "core/disk_file.hpp"

namespace relume {

struct FileCodedSection {
  SectionCoding coding;
  std::uint64_t bytes = 0;  // as stored
  std::uint32_t crc32 = 0;  // of the stored bytes
};

// Appends the section whose raw bytes are all of `raw` (numbers of `element_bytes` bytes) to
// `out`, coded; `entropy_coding` false stores it raw. Each candidate coding is written to a
// temporary file in `scratch_folder` and the smallest is copied.
FileCodedSection append_coded_section(const DiskFile& raw, int element_bytes, bool entropy_coding,
                                      const std::filesystem::path& scratch_folder, DiskFile& out);

}  // namespace relume
