// Fuzz target: the decoder of the weight planes' JPEG 2000 codestream (container/
// jpeg2000_planes.hpp, OpenJPEG in strict mode), which a container's 'weight_planes' section
// feeds. The input's first three bytes give the planes the header would expect (width and height
// 1 to 64, count 1 to 16), the rest is the codestream: it must decode to exactly those planes or
// be refused with a relume::Error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "container/jpeg2000_planes.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const int width = 1 + data[0] % 64, height = 1 + data[1] % 64, count = 1 + data[2] % 16;
  relume::fuzz::expect_only_relume_errors([&] {
    const relume::IntegerPlanes planes =
        relume::decode_jpeg2000_planes(data + 3, size - 3, width, height, count, 1, "fuzz");
    if (planes.width != width || planes.height != height || planes.count != count ||
        planes.samples.size() != std::size_t(width) * std::size_t(height) * std::size_t(count))
      std::abort();
  });
  return 0;
}
