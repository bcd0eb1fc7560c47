// Fuzz target: the .relume container reader after the input's checksums are repaired
// (fuzz_support.hpp), so that a mutated section passes the frame check and reaches its decoder:
// the header's JSON, the bit sets, zstd frames, the filters, the weight prediction and every
// consistency check.
#include <cstddef>
#include <cstdint>
#include <string>

#include "container/container.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  relume::fuzz::repair_container_checksums(bytes);
  relume::fuzz::expect_only_relume_errors([&] {
    relume::ContainerOptions stored;
    relume::decode_container(bytes, "fuzz.relume", &stored);
  });
  return 0;
}
