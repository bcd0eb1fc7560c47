// Laying a compressed field out as .npy arrays in a stored zip.
#include "export/npz_export.hpp"

#include <cstdint>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "export/stored_zip.hpp"
#include "field/npy.hpp"
#include "model/compressed_field_checks.hpp"

namespace relume {
namespace {

using Entries = std::vector<std::pair<std::string, std::string>>;

template <class T>
void add(Entries& entries, const std::string& name, const std::string& descr,
         const std::vector<std::size_t>& shape, const T* data, std::size_t count) {
  entries.emplace_back(name + ".npy", encode_npy_array(descr, shape, data, count * sizeof(T)));
}

void add_scalar(Entries& entries, const std::string& name, std::int64_t value) {
  add(entries, name, "<i8", {}, &value, 1);
}

void add_float(Entries& entries, const std::string& name, float value) {
  add(entries, name, "<f4", {}, &value, 1);
}

// What numpy.load(...)['description'] says: every array and how they make the field.
constexpr const char* description =
    "relume compressed reflectance field (clustered sparse residual factorization): the "
    "arrays it is rebuilt from, exactly.\n"
    "width, height, channels, lights, terms, clusters: int64 sizes. Function p = (y * width + "
    "x) * channels + c is channel c of pixel (x, y) over the lights: R[p] (lights,).\n"
    "stored_function: uint32 (rows,), ascending, the function of each stored row s; cluster: "
    "uint32 (rows,), the row's cluster. W: float32 (rows, terms). F: float32 (clusters, "
    "terms, lights). residual_indptr uint32 (rows + 1,), residual_indices uint32 (nnz,) "
    "(each entry's light), residual_data float32 (nnz,): the residual as CSR, "
    "scipy.sparse.csr_matrix((residual_data, residual_indices, residual_indptr), shape=(rows, "
    "lights)); each row is sorted by |value| descending, so that its prefixes are shorter "
    "residuals. Stored row s is W[s] @ F[cluster[s]] + residual row s.\n"
    "dark_pixels: uint32 (n,), ascending pixel indices y * width + x, inside the mask, "
    "without stored rows: channel c of dark pixel d is dark_gains[d, c] * dark[c]. dark: float32 "
    "(channels, lights); (0, lights) when no pixel is dark. dark_gains: float32 (n, channels). "
    "Every other function is zero "
    "(outside the mask, or all zero).\n"
    "transform: int64, the basis of F, the residual and dark. 0: the lights (identity). 1: "
    "Haar; undo it on each function with the inverse of the orthonormal Haar transform over "
    "the lights, whose forward levels work on the first n values, n = lights, then ceil(n / "
    "2), ... while n > 1: pair (x[2k], x[2k+1]) gives the average (x[2k] + x[2k+1]) / sqrt(2) "
    "at k and the detail (x[2k] - x[2k+1]) / sqrt(2) at ceil(n / 2) + k; an odd last value is "
    "carried as the last average.\n"
    "intensities: float32 (lights, 3), the RGB each captured image was divided by: the field "
    "is in those units, and the image of light i is R[:, i] times intensities[i, c] on "
    "channel c (the row's mean for a 1-channel field), as `relume decompress` writes it.\n"
    "directions: float32 (lights, 3), unit vectors from the object towards the lights, camera "
    "frame (x right, y up, z towards the camera). mask: uint8 (height, width), 1 = inside.\n"
    "Relit under a light vector L (lights, 3), channel c of pixel (x, y) is sum_i R[p, i] "
    "L[i, c] (L's row means for a 1-channel field); when non_negative (bool: the field "
    "compressed had no negative value) and L has no negative entry, negative results are set "
    "to 0.\n"
    "Storage: W holds integers times weight_step, residual_data integers times residual_step, "
    "F[k, j] integers of basis_bits bits times basis_scales[k, j] (float32, float32, int64, "
    "float32 (clusters, terms)); 0 steps, 0 bits and (0, terms) scales: stored as floats. The "
    "float32 arrays hold the exact values they stand for.";

}  // namespace

std::string compressed_field_npz(const CompressedField& field) {
  validate_compressed_field(field, "export");
  const std::size_t rows = field.stored_rows();
  const auto lights = std::size_t(field.lights);
  Entries entries;
  add_scalar(entries, "width", field.width);
  add_scalar(entries, "height", field.height);
  add_scalar(entries, "channels", field.channels);
  add_scalar(entries, "lights", field.lights);
  add_scalar(entries, "terms", field.terms);
  add_scalar(entries, "clusters", field.clusters);
  add_scalar(entries, "transform", static_cast<std::int64_t>(field.transform));
  add(entries, "mask", "|u1", {std::size_t(field.height), std::size_t(field.width)},
      field.mask.data(), field.mask.size());
  add(entries, "directions", "<f4", {lights, 3}, field.directions.data(), lights * 3);
  add(entries, "intensities", "<f4", {lights, 3}, field.intensities.data(), lights * 3);
  add(entries, "stored_function", "<u4", {rows}, field.stored_function.data(), rows);
  add(entries, "cluster", "<u4", {rows}, field.cluster.data(), rows);
  add(entries, "W", "<f4", {rows, std::size_t(field.terms)}, field.weights.data(),
      std::size_t(field.weights.size()));
  add(entries, "F", "<f4", {std::size_t(field.clusters), std::size_t(field.terms), lights},
      field.bases.data(), field.bases.size());
  add(entries, "residual_indptr", "<u4", {field.residual.row_offsets.size()},
      field.residual.row_offsets.data(), field.residual.row_offsets.size());
  add(entries, "residual_indices", "<u4", {field.residual.nonzeros()},
      field.residual.light_index.data(), field.residual.nonzeros());
  add(entries, "residual_data", "<f4", {field.residual.nonzeros()}, field.residual.values.data(),
      field.residual.nonzeros());
  add(entries, "dark_pixels", "<u4", {field.dark_pixels.size()}, field.dark_pixels.data(),
      field.dark_pixels.size());
  add(entries, "dark", "<f4", {field.dark.size() / lights, lights}, field.dark.data(),
      field.dark.size());
  std::vector<float> gains(field.dark_pixels.size() * std::size_t(field.channels));
  for (std::size_t v = 0; v < gains.size(); ++v)
    gains[v] = dark_gain(field, v / std::size_t(field.channels), int(v % field.channels));
  add(entries, "dark_gains", "<f4", {field.dark_pixels.size(), std::size_t(field.channels)},
      gains.data(), gains.size());
  const bool non_negative = field.non_negative;
  add(entries, "non_negative", "|b1", {}, &non_negative, 1);
  const ValueQuantization& quantization = field.quantization;
  add_float(entries, "weight_step", quantization.weight_step);
  add_float(entries, "residual_step", quantization.residual_step);
  add_scalar(entries, "basis_bits", quantization.basis_bits);
  const auto terms = std::size_t(field.terms);
  add(entries, "basis_scales", "<f4", {terms ? quantization.basis_scales.size() / terms : 0, terms},
      quantization.basis_scales.data(), quantization.basis_scales.size());
  const std::string text = description;
  std::vector<char32_t> utf32(text.begin(), text.end());  // ASCII: one code point per byte
  add(entries, "description", "<U" + std::to_string(utf32.size()), {}, utf32.data(), utf32.size());
  return stored_zip(entries);
}

void write_compressed_field_npz(const std::filesystem::path& path, const CompressedField& field) {
  write_file_atomically(path, compressed_field_npz(field));
}

}  // namespace relume
