// NumPy .npy files for matrices, so that `relume factor` can be driven from Python: 2-D arrays of
// float32 or float64, C order (row-major) or Fortran order, either byte order, format versions
// 1.0, 2.0 and 3.0. Writes are C order, little-endian, version 1.0, atomic. Anything else (other
// dtypes, other ranks, a bad magic string, a malformed header, truncated or oversized data) is
// refused with an Error that names the file and what was expected.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace relume {

enum class NpyDtype { float32, float64 };

struct NpyMatrix {
  Eigen::MatrixXd values;
  NpyDtype dtype = NpyDtype::float64;  // as stored in the file
};

NpyMatrix read_npy_matrix(const std::filesystem::path& path);
// Parses the bytes of a .npy file; `name` is used in error messages.
NpyMatrix parse_npy_matrix(const std::string& bytes, const std::string& name);

// A version 1.0 .npy file of any array: `descr` is NumPy's type string ("<f4", "<u4", "|u1",
// "<i8", "<U12"), `shape` its dimensions (empty: a scalar), `data` the `bytes` of its values in C
// order and the byte order of descr (this machine's, little-endian). Throws Error when `bytes`
// is not the shape's element count times a whole element size, or the header outgrows 64 KiB.
std::string encode_npy_array(const std::string& descr, const std::vector<std::size_t>& shape,
                             const void* data, std::size_t bytes);

// Throws Error when a value does not fit float32 (|value| > FLT_MAX); NaN and Inf are kept.
std::string encode_npy_matrix(const Eigen::MatrixXd& values, NpyDtype dtype);
void write_npy_matrix(const std::filesystem::path& path, const Eigen::MatrixXd& values,
                      NpyDtype dtype);

}  // namespace relume
