// Fuzz target: the .npz export (export/npz_export.hpp) read back. The input is a container (its
// checksums repaired, fuzz_support.hpp); when it decodes, its .npz is walked as numpy.load reads
// it: stored zip entries one after another, each with its name, sizes and CRC-32 right, each an
// .npy array, until the central directory; the float32 matrices W and directions must parse
// (field/npy.hpp) back to the field's values.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <relume/error.hpp>
#include <string>

#include "container/container.hpp"
#include "core/crc32.hpp"
#include "export/npz_export.hpp"
#include "field/npy.hpp"
#include "fuzz_support.hpp"

namespace {

std::uint64_t load(const std::string& bytes, std::size_t at, int width) {
  if (at + width > bytes.size()) std::abort();  // the archive ends inside a header
  std::uint64_t value = 0;
  for (int b = 0; b < width; ++b)
    value |= std::uint64_t(static_cast<unsigned char>(bytes[at + b])) << (8 * b);
  return value;
}

// The entries of a stored zip, by name; aborts on anything numpy.load would refuse.
std::map<std::string, std::string> read_stored_zip(const std::string& zip) {
  std::map<std::string, std::string> entries;
  std::size_t at = 0;
  while (load(zip, at, 4) == 0x04034b50) {  // a local file header
    const std::uint64_t method = load(zip, at + 8, 2), crc = load(zip, at + 14, 4);
    const std::uint64_t stored = load(zip, at + 18, 4), size = load(zip, at + 22, 4);
    const std::uint64_t name_bytes = load(zip, at + 26, 2), extra = load(zip, at + 28, 2);
    const std::size_t data = at + 30 + name_bytes + extra;
    if (method != 0 || stored != size || data + size > zip.size()) std::abort();
    const std::string name = zip.substr(at + 30, name_bytes);
    const std::string contents = zip.substr(data, size);
    if (relume::crc32(contents) != crc || contents.rfind("\x93NUMPY", 0) != 0) std::abort();
    if (!entries.emplace(name, contents).second) std::abort();
    at = data + size;
  }
  if (load(zip, at, 4) != 0x02014b50) std::abort();  // the central directory follows
  return entries;
}

void expect_float32_matrix(const std::map<std::string, std::string>& entries,
                           const std::string& name, const float* values, std::size_t rows,
                           std::size_t columns) {
  if (rows == 0 || columns == 0) return;
  const auto entry = entries.find(name);
  if (entry == entries.end()) std::abort();
  const relume::NpyMatrix matrix = relume::parse_npy_matrix(entry->second, name);
  if (matrix.dtype != relume::NpyDtype::float32 || std::size_t(matrix.values.rows()) != rows ||
      std::size_t(matrix.values.cols()) != columns)
    std::abort();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < columns; ++c)
      if (float(matrix.values(Eigen::Index(r), Eigen::Index(c))) != values[r * columns + c])
        std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  relume::fuzz::repair_container_checksums(bytes);
  relume::CompressedField field;
  try {
    field = relume::decode_container(bytes, "fuzz.relume");
  } catch (const relume::Error&) {
    return 0;
  }
  const auto entries = read_stored_zip(relume::compressed_field_npz(field));
  expect_float32_matrix(entries, "W.npy", field.weights.data(), std::size_t(field.weights.rows()),
                        std::size_t(field.terms));
  expect_float32_matrix(entries, "directions.npy", field.directions.data(),
                        std::size_t(field.directions.rows()), 3);
  return 0;
}
