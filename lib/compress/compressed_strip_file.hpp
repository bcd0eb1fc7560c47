// The compressed field of a streamed compression as its build pass makes it, strip by strip, kept
// on disk instead of in memory (a 24-megapixel capture's stored rows take gigabytes): each
// strip's stored rows (function indices, clusters, W, residual rows) go to a temporary file in the
// scratch folder (core/disk_file.hpp), and everything else about the field (size, mask, dark
// pixels and model, lights) to a shell in memory. Strips are read back one at a time to choose
// the stored precision, to write the container (container/container_strips.hpp) and to measure
// the error.
#pragma once

#include <cstdint>
#include <filesystem>
#include <relume/compressed_field.hpp>
#include <string>
#include <vector>

#include "core/disk_file.hpp"

namespace relume {

class CompressedStripFile {
 public:
  // The file `.tmp-<pid>-<name>` in `folder`.
  CompressedStripFile(const std::filesystem::path& folder, const std::string& name);

  // Appends `strip`, the pixel rows below those appended before (a compressed field of its own,
  // as compressed_rows cuts one).
  void append(const CompressedField& strip);

  // Strip s as appended, with the shell's bases, quantization and dark model.
  CompressedField read(std::size_t s) const;

  std::size_t strips() const { return extents_.size(); }
  // Every strip's first pixel row.
  std::vector<int> first_rows() const;
  // The field appended so far without its stored rows; bases and quantization are the caller's
  // to set.
  CompressedField& shell() { return shell_; }
  const CompressedField& shell() const { return shell_; }
  // Stored rows of each cluster over all strips (clusters as the shell says).
  std::vector<std::size_t> cluster_sizes() const;
  std::uint64_t stored_rows() const { return stored_rows_; }
  std::uint64_t bytes() const { return file_.size(); }

 private:
  struct Extent {
    std::uint64_t offset = 0;
    std::uint32_t rows = 0, nonzeros = 0;
    int first_row = 0, height = 0;
  };
  DiskFile file_;
  CompressedField shell_;
  std::vector<Extent> extents_;
  std::vector<std::size_t> cluster_sizes_;
  std::uint64_t stored_rows_ = 0;
};

}  // namespace relume
