// A file read and written at offsets, for data that does not fit in memory (the scratch rows and
// compressed strips of a streamed compression, the raw sections of a container written strip by
// strip, the container itself as it is written). Every failure (a full disk, a short file) is an
// Error naming the file.
//  - DiskFile::temporary: `.tmp-<pid>-<name>` in a folder (created if missing; stale ones of
//    killed runs removed first), registered for the signal handler (core/temporary_files.hpp) and
//    removed when the object goes, so that neither an error nor an interruption leaves it behind.
//  - DiskFile::create: a file at a given path (write_atomically's temporary), created or
//    truncated; its owner renames or removes it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/temporary_files.hpp"

namespace relume {

class DiskFile {
 public:
  // `what` names the file in messages ("scratch file", "container", ...).
  static DiskFile temporary(const std::filesystem::path& folder, const std::string& name,
                            const std::string& what);
  static DiskFile create(const std::filesystem::path& path, const std::string& what);
  ~DiskFile();
  DiskFile(DiskFile&& other) noexcept;
  DiskFile(const DiskFile&) = delete;
  DiskFile& operator=(const DiskFile&) = delete;
  DiskFile& operator=(DiskFile&&) = delete;

  void write_at(std::uint64_t offset, const void* data, std::size_t bytes);
  void read_at(std::uint64_t offset, void* data, std::size_t bytes) const;
  // Writes at the end of what was written so far.
  void append(const void* data, std::size_t bytes);
  // Closes it (a temporary is removed); throws Error when the last writes fail to reach the disk.
  void close();

  std::uint64_t size() const { return size_; }  // the end of what was written
  const std::filesystem::path& path() const { return path_; }

 private:
  DiskFile(std::filesystem::path path, std::string what, bool temporary);

  std::filesystem::path path_;
  std::string what_;
  bool temporary_ = false;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::unique_ptr<TemporaryPathRegistration> registration_;
};

}  // namespace relume
