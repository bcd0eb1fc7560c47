// Fuzz target: the .relume container reader on arbitrary bytes, as they are. Most mutations
// break a CRC-32 and are refused by the frame check; fuzz_container_repaired.cpp repairs the
// checksums so that mutations reach the section decoders.
#include <cstddef>
#include <cstdint>
#include <string>

#include "container/container.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  relume::fuzz::expect_only_relume_errors([&] {
    relume::ContainerOptions stored;
    relume::decode_container(bytes, "fuzz.relume", &stored);
  });
  return 0;
}
