// A compressed field as a NumPy .npz archive, for tools outside relume (numpy.load reads it; no
// pickle). Arrays, little-endian, C order, named as in relume/compressed_field.hpp:
//   width, height, channels, lights, terms, clusters   int64 scalars
//   transform            int64 scalar: 0 identity, 1 Haar (F and the residual are in that basis)
//   mask                 uint8 (height, width), 1 = inside
//   directions           float32 (lights, 3), unit vectors towards each light, camera frame
//   intensities          float32 (lights, 3), per-light RGB the images were divided by
//   stored_function      uint32 (rows,), the function p = (y * width + x) * channels + c of each
//                        stored row
//   cluster              uint32 (rows,), each stored row's cluster
//   W                    float32 (rows, terms)
//   F                    float32 (clusters, terms, lights)
//   residual_indptr      uint32 (rows + 1,)  \  the residual as CSR, rows sorted by |value|
//   residual_indices     uint32 (nnz,)        > descending: scipy.sparse.csr_matrix((data,
//   residual_data        float32 (nnz,)      /  indices, indptr), shape=(rows, lights))
//   description          a unicode string saying the same in one paragraph
// so that row s of the field is W[s] @ F[cluster[s]] + residual[s] (then the inverse transform).
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
