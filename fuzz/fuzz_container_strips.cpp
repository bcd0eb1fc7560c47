// Fuzz target: the container writer for fields in strips (container/container_strips.hpp)
// against the writer of whole fields. The input is a container (its checksums repaired,
// fuzz_support.hpp) and a last byte that chooses the strip height; when the container decodes,
// its field is written both ways with the options it was stored with. Both writers must refuse
// it, or both write it, and then the two files must hold the same field.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <relume/container.hpp>
#include <relume/error.hpp>
#include <string>

#include "container/container.hpp"
#include "container/container_strips.hpp"
#include "fuzz_support.hpp"
#include "model/compressed_field_rows.hpp"

namespace {

relume::CompressedFieldStrips strips_of(const relume::CompressedField& field, int rows) {
  relume::CompressedFieldStrips strips;
  strips.shell = field;
  strips.shell.stored_function.clear();
  strips.shell.cluster.clear();
  strips.shell.weights.resize(0, field.terms);
  strips.shell.residual = {};
  for (int y = 0; y < field.height; y += rows) strips.first_rows.push_back(y);
  strips.strip = [&field, rows](std::size_t s) {
    const int first = int(s) * rows;
    return relume::compressed_rows(field, first, std::min(rows, field.height - first));
  };
  return strips;
}

// The field `path` holds, encoded again in memory as it was stored.
std::string contents(const std::filesystem::path& path) {
  relume::ContainerOptions stored;
  const relume::CompressedField field = relume::read_container(path, &stored);
  return relume::encode_container(field, stored, "re-encoding", nullptr);
}

// Runs `write`; the message of the relume::Error it throws, or nullopt.
template <typename Write>
std::optional<std::string> refusal(const Write& write) {
  try {
    write();
    return std::nullopt;
  } catch (const relume::Error& e) {
    return std::string(e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  std::string bytes(reinterpret_cast<const char*>(data), size - 1);
  const int rows = 1 + data[size - 1] % 8;
  relume::fuzz::repair_container_checksums(bytes);
  relume::CompressedField field;
  relume::ContainerOptions stored;
  try {
    field = relume::decode_container(bytes, "fuzz.relume", &stored);
  } catch (const relume::Error&) {
    return 0;
  }
  const auto& folder = relume::fuzz::scratch_folder();
  const auto whole = refusal([&] { relume::write_container(folder / "whole.relume", field, stored); });
  const auto in_strips = refusal([&] {
    relume::write_container_strips(folder / "strips.relume", strips_of(field, rows), stored,
                                   folder / "strips-scratch");
  });
  if (whole.has_value() != in_strips.has_value()) std::abort();
  if (!whole && contents(folder / "whole.relume") != contents(folder / "strips.relume"))
    std::abort();
  return 0;
}
