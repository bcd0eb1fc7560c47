// Implementation of files read and written at offsets (see disk_file.hpp).
#include "core/disk_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <relume/error.hpp>
#include <utility>

namespace relume {
namespace fs = std::filesystem;

DiskFile::DiskFile(fs::path path, std::string what, bool temporary)
    : path_(std::move(path)), what_(std::move(what)), temporary_(temporary) {
  if (temporary_)
    registration_ =
        std::make_unique<TemporaryPathRegistration>(path_, TemporaryPathRegistration::Kind::file);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, temporary_ ? 0600 : 0644);
  if (fd_ < 0)
    throw Error("cannot write the " + what_ + " " + path_.string() + ": " + std::strerror(errno));
}

DiskFile DiskFile::temporary(const fs::path& folder, const std::string& name,
                             const std::string& what) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error)
    throw Error("cannot create the scratch folder " + folder.string() + ": " + error.message());
  remove_stale_temporaries(folder / name);
  return DiskFile(temporary_path_for(folder / name), what, true);
}

DiskFile DiskFile::create(const fs::path& path, const std::string& what) {
  return DiskFile(path, what, false);
}

DiskFile::DiskFile(DiskFile&& other) noexcept
    : path_(std::move(other.path_)),
      what_(std::move(other.what_)),
      temporary_(other.temporary_),
      fd_(std::exchange(other.fd_, -1)),
      size_(other.size_),
      registration_(std::move(other.registration_)) {
  other.temporary_ = false;
}

DiskFile::~DiskFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_) return;
  std::error_code ignored;
  fs::remove(path_, ignored);
}

void DiskFile::close() {
  const int fd = std::exchange(fd_, -1);
  if (fd >= 0 && ::close(fd) != 0)
    throw Error("cannot write the " + what_ + " " + path_.string() + ": " + std::strerror(errno));
}

void DiskFile::write_at(std::uint64_t offset, const void* data, std::size_t bytes) {
  const char* next = static_cast<const char*>(data);
  const std::uint64_t end = offset + bytes;
  while (bytes > 0) {
    const ssize_t written = ::pwrite(fd_, next, bytes, off_t(offset));
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0)
      throw Error("cannot write the " + what_ + " " + path_.string() + ": " +
                  std::strerror(written < 0 ? errno : ENOSPC));
    next += written;
    bytes -= std::size_t(written);
    offset += std::uint64_t(written);
  }
  size_ = std::max(size_, end);
}

void DiskFile::read_at(std::uint64_t offset, void* data, std::size_t bytes) const {
  if (offset + bytes > size_)
    throw Error(what_ + " " + path_.string() + ": bytes " + std::to_string(offset) + " to " +
                std::to_string(offset + bytes) + " are beyond the " + std::to_string(size_) +
                " written");
  char* next = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t got = ::pread(fd_, next, bytes, off_t(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw Error("cannot read the " + what_ + " " + path_.string() + ": " +
                  (got < 0 ? std::strerror(errno) : "it is shorter than written"));
    next += got;
    bytes -= std::size_t(got);
    offset += std::uint64_t(got);
  }
}

void DiskFile::append(const void* data, std::size_t bytes) { write_at(size_, data, bytes); }

}  // namespace relume
