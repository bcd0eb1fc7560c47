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

constexpr const char* description =
    "relume compressed reflectance field (clustered sparse residual factorization). Stored row s "
    "is function stored_function[s] = (y * width + x) * channels + c; it is reconstructed as "
    "W[s] @ F[cluster[s]] + the CSR residual row s (residual_indptr, residual_indices, "
    "residual_data; entries sorted by |value| descending), in the basis named by transform "
    "(0 identity: the light basis; 1 Haar: apply the inverse orthonormal Haar transform over "
    "lights). Functions that are not stored are zero. Relit image = reconstruction times a light "
    "vector (lights x RGB).";

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
  const std::string text = description;
  std::vector<char32_t> utf32(text.begin(), text.end());  // ASCII: one code point per byte
  add(entries, "description", "<U" + std::to_string(utf32.size()), {}, utf32.data(), utf32.size());
  return stored_zip(entries);
}

void write_compressed_field_npz(const std::filesystem::path& path, const CompressedField& field) {
  write_file_atomically(path, compressed_field_npz(field));
}

}  // namespace relume
