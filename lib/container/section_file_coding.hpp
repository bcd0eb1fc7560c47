// Section coding (container/section_coding.hpp) of a section too large for memory: its raw bytes
// are in a file and go through the filter and zstd a few megabytes at a time. The result is the
// coding code_section would choose for the same bytes (the smallest of raw and zstd after each
// filter), and the same decoded contents.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "container/section_coding.hpp"
#include "core/disk_file.hpp"

namespace relume {

struct FileCodedSection {
  SectionCoding coding;
  std::uint64_t bytes = 0;        // as stored
  std::uint32_t crc32 = 0;        // of the stored bytes (append_coded_section sets it)
  std::optional<DiskFile> coded;  // the stored bytes when coded; else the raw file's are stored
};

// Every section whose raw bytes are all of *raws[i] (numbers of element_bytes[i] bytes) coded as
// code_section would code it: the smallest of raw and zstd after each candidate filter (the
// first of equal ones); `entropy_coding` false keeps them raw. Each candidate is coded into a
// temporary file in `scratch_folder`, the candidates of all the sections on `threads` threads at
// once; a file that is not the smallest of its section so far is dropped as soon as it is done.
// Progress is reported as `title`.
std::vector<FileCodedSection> code_section_files(const std::vector<const DiskFile*>& raws,
                                                 const std::vector<int>& element_bytes,
                                                 bool entropy_coding,
                                                 const std::filesystem::path& scratch_folder,
                                                 unsigned threads, const std::string& title);

// Appends the stored bytes of `section`, coded from `raw` by code_section_files, to `out`.
void append_coded_section(const DiskFile& raw, FileCodedSection& section, DiskFile& out);

}  // namespace relume
