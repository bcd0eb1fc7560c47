// The scratch store of a streamed compression: the working rows (unit-norm reflectance functions,
// compress/cluster_model.hpp) written once, in order, to a file of float16 values, and read back
// a block at a time by every later pass, so that passes over a field larger than memory do not
// decode its images again. The file is a temporary (core/temporary_files.hpp) in the folder
// given: removed when the store goes, on error, and by a second Ctrl-C; a later run's stale
// cleanup removes what a killed one left.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "compress/cluster_model.hpp"
#include "core/disk_file.hpp"

namespace relume {

// Rows as a scratch file holds them: float16 values (bit patterns) and their norms, for moving
// rows from one store to another unchanged (compress/rank_exchange.hpp).
struct ScratchBlock {
  std::vector<std::uint16_t> halves;
  std::vector<float> norms;
};

class ScratchRows {
 public:
  // Creates the file `.tmp-<pid>-<name>` in `folder` (created if missing); values are converted
  // by `threads` workers (0: all cores). Throws Error naming it when it cannot be written.
  ScratchRows(const std::filesystem::path& folder, const std::string& name, int lights,
              unsigned threads = 0);

  // Appends `rows` (their values rounded to float16; the norms are kept exactly, in memory).
  // Throws Error naming the file when the disk refuses the bytes.
  void append(const WorkingRows& rows);
  // Rows [first, first + count) as float32, unit norm again after the rounding.
  WorkingRows read(std::size_t first, std::size_t count) const;
  // Rows [first, first + count) as stored, and appending such rows.
  ScratchBlock read_block(std::size_t first, std::size_t count) const;
  void append_block(const ScratchBlock& block);

  std::size_t rows() const { return norms_.size(); }
  int lights() const { return lights_; }
  std::uint64_t bytes() const { return std::uint64_t(rows()) * std::uint64_t(lights_) * 2; }
  const std::filesystem::path& path() const { return file_.path(); }

 private:
  DiskFile file_;
  int lights_ = 0;
  unsigned threads_ = 0;
  std::vector<float> norms_;
};

}  // namespace relume
