// Implementation of the streamed compression's scratch store (see scratch_rows.hpp).
#include "compress/scratch_rows.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "container/container_bytes.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace fs = std::filesystem;

ScratchRows::ScratchRows(const fs::path& folder, const std::string& name, int lights,
                         unsigned threads)
    : file_(DiskFile::temporary(folder, name, "scratch file")), lights_(lights), threads_(threads) {}

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
    throw Error("scratch file " + path().string() + ": a block of " +
                std::to_string(block.halves.size()) + " values for " +
                std::to_string(block.norms.size()) + " rows of " + std::to_string(lights_) +
                " lights");
  file_.write_at(bytes(), block.halves.data(), block.halves.size() * sizeof(std::uint16_t));
  norms_.insert(norms_.end(), block.norms.begin(), block.norms.end());
}

ScratchBlock ScratchRows::read_block(std::size_t first, std::size_t count) const {
  if (first + count > rows())
    throw Error("scratch file " + path().string() + ": rows " + std::to_string(first) + " to " +
                std::to_string(first + count) + " are beyond its " + std::to_string(rows()));
  ScratchBlock block;
  block.halves.resize(count * std::size_t(lights_));
  file_.read_at(first * std::size_t(lights_) * sizeof(std::uint16_t), block.halves.data(),
                block.halves.size() * sizeof(std::uint16_t));
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
