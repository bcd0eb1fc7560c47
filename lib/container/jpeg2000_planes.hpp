// Integer image planes coded as one JPEG 2000 codestream by OpenJPEG (libopenjp2): every plane is
// a component of one image, irreversible 9/7 wavelet, no colour transform of the coder's own, one
// quality layer. The coder's rate allocation (PCRD) spends the bytes over all planes by the
// squared error they save, so planes whose values are in a common unit share one budget fairly.
// This is how the container codes the weight planes (model/weight_planes.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace relume {

// `count` planes of width x height signed 16-bit samples, plane after plane, each row-major.
struct IntegerPlanes {
  int width = 0;
  int height = 0;
  int count = 0;
  std::vector<std::int32_t> samples;  // count * width * height, each in [-32767, 32767]
};

// The planes coded in at most `max_bytes` bytes (rate allocation, then a few corrections: the
// codestream lands within about 1% under the bound when the planes need that many bytes, fewer
// when they need less). When no codestream fits (the headers alone take 3 bytes a plane), the
// smallest one made, which the caller sees is larger. `threads`: OpenJPEG's worker threads
// (0: one per core). Throws Error when OpenJPEG fails.
std::vector<std::uint8_t> encode_jpeg2000_planes(const IntegerPlanes& planes,
                                                 std::uint64_t max_bytes, unsigned threads);

// Decodes a codestream that must hold exactly `count` signed 16-bit planes of width x height.
// Throws Error("<where>: ...") for anything else: a damaged or truncated codestream, other
// dimensions, components, precision or sub-sampling.
IntegerPlanes decode_jpeg2000_planes(const std::uint8_t* data, std::size_t size, int width,
                                     int height, int count, unsigned threads,
                                     const std::string& where);

}  // namespace relume
