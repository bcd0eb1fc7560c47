// Implementation of the streamed compression's scratch store (see scratch_rows.hpp).
#include "compress/scratch_rows.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <relume/error.hpp>

#include "container/container_bytes.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace fs = std::filesystem;

ScratchRows::ScratchRows(const fs::path& folder, const std::string& name, int lights,
                         unsigned threads)
    : lights_(lights), threads_(threads) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error)
    throw Error("cannot create the scratch folder " + folder.string() + ": " + error.message());
  path_ = temporary_path_for(folder / name);
  remove_stale_temporaries(folder / name);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0)
    throw Error("cannot write the scratch file " + path_.string() + ": " + std::strerror(errno));
  registration_ =
      std::make_unique<TemporaryPathRegistration>(path_, TemporaryPathRegistration::Kind::file);
}

ScratchRows::~ScratchRows() {
  if (fd_ >= 0) ::close(fd_);
  std::error_code ignored;
  fs::remove(path_, ignored);
}

void ScratchRows::append(const WorkingRows& rows) {
  ScratchBlock block;
  block.halves.resize(rows.rows() * std::size_t(lights_));
  const float* data = rows.values.data();
  parallel_for(rows.rows(), threads_, [&](std::size_t r, unsigned) {
    for (std::size_t v = r * std::size_t(lights_); v < (r + 1) * std::size_t(lights_); ++v)
      block.halves[v] = float_to_half_bits(data[v]);
  });
  block.norms = rows.norms;
  append_block(block);
}

void ScratchRows::append_block(const ScratchBlock& block) {
  if (block.halves.size() != block.norms.size() * std::size_t(lights_))
    throw Error("scratch file " + path_.string() + ": a block of " +
                std::to_string(block.halves.size()) + " values for " +
                std::to_string(block.norms.size()) + " rows of " + std::to_string(lights_) +
                " lights");
  off_t offset = off_t(bytes());
  const char* data_bytes = reinterpret_cast<const char*>(block.halves.data());
  std::size_t left = block.halves.size() * sizeof(std::uint16_t);
  while (left > 0) {
    const ssize_t written = ::pwrite(fd_, data_bytes, left, offset);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0)
      throw Error("cannot write the scratch file " + path_.string() + ": " +
                  std::strerror(written < 0 ? errno : ENOSPC));
    data_bytes += written;
    left -= std::size_t(written);
    offset += written;
  }
  norms_.insert(norms_.end(), block.norms.begin(), block.norms.end());
}

ScratchBlock ScratchRows::read_block(std::size_t first, std::size_t count) const {
  if (first + count > rows())
    throw Error("scratch file " + path_.string() + ": rows " + std::to_string(first) + " to " +
                std::to_string(first + count) + " are beyond its " + std::to_string(rows()));
  ScratchBlock block;
  block.halves.resize(count * std::size_t(lights_));
  char* data_bytes = reinterpret_cast<char*>(block.halves.data());
  std::size_t left = block.halves.size() * sizeof(std::uint16_t);
  off_t offset = off_t(first * std::size_t(lights_) * sizeof(std::uint16_t));
  while (left > 0) {
    const ssize_t got = ::pread(fd_, data_bytes, left, offset);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw Error("cannot read the scratch file " + path_.string() + ": " +
                  (got < 0 ? std::strerror(errno) : "it is shorter than written"));
    data_bytes += got;
    left -= std::size_t(got);
    offset += got;
  }
  block.norms.assign(norms_.begin() + std::ptrdiff_t(first),
                     norms_.begin() + std::ptrdiff_t(first + count));
  return block;
}

WorkingRows ScratchRows::read(std::size_t first, std::size_t count) const {
  ScratchBlock block = read_block(first, count);
  WorkingRows rows;
  rows.values.resize(Eigen::Index(count), lights_);
  rows.norms = std::move(block.norms);
  parallel_for(count, threads_, [&](std::size_t r, unsigned) {
    float* out = rows.values.data() + r * std::size_t(lights_);
    double energy = 0;
    for (int i = 0; i < lights_; ++i) {
      out[i] = half_bits_to_float(block.halves[r * std::size_t(lights_) + std::size_t(i)]);
      energy += double(out[i]) * out[i];
    }
    const float scale = energy > 0 ? float(1.0 / std::sqrt(energy)) : 1.0f;
    for (int i = 0; i < lights_; ++i) out[i] *= scale;
  });
  return rows;
}

}  // namespace relume
