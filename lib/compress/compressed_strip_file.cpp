// Implementation of the on-disk compressed strips (see compressed_strip_file.hpp).
#include "compress/compressed_strip_file.hpp"

#include <relume/error.hpp>

#include "model/compressed_field_rows.hpp"

namespace relume {

CompressedStripFile::CompressedStripFile(const std::filesystem::path& folder,
                                         const std::string& name)
    : file_(DiskFile::temporary(folder, name, "compressed strip file")) {}

void CompressedStripFile::append(const CompressedField& strip) {
  const std::size_t rows = strip.stored_rows();
  const ResidualRows& e = strip.residual;
  if (strip.weights.rows() != Eigen::Index(rows) || strip.cluster.size() != rows ||
      e.rows() != rows)
    throw Error("internal: a compressed strip of " + std::to_string(rows) +
                " stored rows has inconsistent arrays");
  Extent extent;
  extent.offset = file_.size();
  extent.rows = std::uint32_t(rows);
  extent.nonzeros = std::uint32_t(e.nonzeros());
  extent.first_row = shell_.height;
  extent.height = strip.height;
  // The stored rows one array after the other: function indices, clusters (u32), W (f32, rows x
  // terms), residual row offsets (u32, rows + 1), light indices (u32) and values (f32).
  file_.append(strip.stored_function.data(), rows * 4);
  file_.append(strip.cluster.data(), rows * 4);
  file_.append(strip.weights.data(), std::size_t(strip.weights.size()) * 4);
  file_.append(e.row_offsets.data(), e.row_offsets.size() * 4);
  file_.append(e.light_index.data(), e.nonzeros() * 4);
  file_.append(e.values.data(), e.nonzeros() * 4);
  extents_.push_back(extent);
  stored_rows_ += rows;
  cluster_sizes_.resize(std::size_t(strip.clusters), 0);
  for (const std::uint32_t k : strip.cluster) ++cluster_sizes_[k];

  // The shell: the strip without its stored rows.
  CompressedField rowless;
  rowless.width = strip.width;
  rowless.height = strip.height;
  rowless.channels = strip.channels;
  rowless.lights = strip.lights;
  rowless.terms = strip.terms;
  rowless.clusters = strip.clusters;
  rowless.transform = strip.transform;
  rowless.mask = strip.mask;
  rowless.dark_pixels = strip.dark_pixels;
  if (!strip.dark_pixels.empty()) rowless.dark = strip.dark;
  rowless.dark_gains = strip.dark_gains;
  rowless.dark_gain_step = strip.dark_gain_step;
  rowless.non_negative = strip.non_negative;
  if (shell_.height == 0) {
    rowless.directions = strip.directions;
    rowless.intensities = strip.intensities;
  }
  rowless.weights.resize(0, strip.terms);
  append_compressed_rows(shell_, rowless);
}

CompressedField CompressedStripFile::read(std::size_t s) const {
  const Extent& extent = extents_.at(s);
  CompressedField strip = compressed_rows(shell_, extent.first_row, extent.height);
  const std::size_t rows = extent.rows, nonzeros = extent.nonzeros;
  strip.stored_function.resize(rows);
  strip.cluster.resize(rows);
  strip.weights.resize(Eigen::Index(rows), shell_.terms);
  strip.residual.row_offsets.resize(rows + 1);
  strip.residual.light_index.resize(nonzeros);
  strip.residual.values.resize(nonzeros);
  std::uint64_t at = extent.offset;
  const auto take = [&](void* data, std::size_t bytes) {
    file_.read_at(at, data, bytes);
    at += bytes;
  };
  take(strip.stored_function.data(), rows * 4);
  take(strip.cluster.data(), rows * 4);
  take(strip.weights.data(), std::size_t(strip.weights.size()) * 4);
  take(strip.residual.row_offsets.data(), (rows + 1) * 4);
  take(strip.residual.light_index.data(), nonzeros * 4);
  take(strip.residual.values.data(), nonzeros * 4);
  return strip;
}

std::vector<int> CompressedStripFile::first_rows() const {
  std::vector<int> rows;
  for (const Extent& extent : extents_) rows.push_back(extent.first_row);
  return rows;
}

std::vector<std::size_t> CompressedStripFile::cluster_sizes() const {
  std::vector<std::size_t> sizes = cluster_sizes_;
  sizes.resize(std::size_t(shell_.clusters), 0);
  return sizes;
}

}  // namespace relume
