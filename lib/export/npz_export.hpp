// A compressed field as a NumPy .npz archive, for tools outside relume (numpy.load reads it; no
// pickle): every array the field is rebuilt from, exactly (sizes, mask, lights and intensities,
// clusters, W, F, the residual as CSR, the dark model, the basis transform, the quantization as
// stored), little-endian, C order, named as in relume/compressed_field.hpp, and `description`, a
// unicode string that says what each array is and how they make the field and its images (its
// text is in npz_export.cpp).
#pragma once

#include <filesystem>
#include <relume/compressed_field.hpp>
#include <string>

namespace relume {

// The .npz bytes. Throws Error when an array does not fit a zip without zip64 (4 GiB).
std::string compressed_field_npz(const CompressedField& field);

// Writes compressed_field_npz(field) to `path` atomically.
void write_compressed_field_npz(const std::filesystem::path& path, const CompressedField& field);

}  // namespace relume
