// Fuzz target: the .npy matrix reader (magic, version, header dict, dtype, shape, data size).
#include <cstddef>
#include <cstdint>
#include <string>

#include "field/npy.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  relume::fuzz::expect_only_relume_errors([&] { relume::parse_npy_matrix(bytes, "fuzz.npy"); });
  return 0;
}
