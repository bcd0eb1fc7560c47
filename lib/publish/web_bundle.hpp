// The published page's binary files ("bundles"): a few arrays in one file, each filtered as the
// container filters its sections (container/section_coding.hpp: none, a byte shuffle, or a delta
// then shuffle) and compressed with raw deflate (RFC 1951), whichever filter gives the fewest
// bytes, or stored raw when none is smaller. Deflate, not the container's zstd, because every
// browser decodes it natively (DecompressionStream('deflate-raw')); on the synthetic 640 x 640
// scene's tiles it costs 3% more bytes than zstd and decodes about ten times faster than zstd
// in JavaScript. The page (web/field_data.js) undoes the filters.
//
// File: "RLWB", then little-endian uint32s: the version (1), the number of arrays n, and per
// array its coding word (bits 0-7: 0 raw, 2 deflate; 8-15: the filter, 0 none, 1 shuffle,
// 2 delta; 16-23: the element bytes), its coded bytes and its raw bytes; then the arrays' coded
// bytes one after the other. What each array is (its name and element type) the manifest says,
// in the same order.
#pragma once

#include <string>
#include <vector>

namespace relume {

struct BundleArray {
  std::string name;
  std::string type;  // "uint8", "uint16", "uint32", "int16", "float32" or "med16" (web_layout.hpp)
  std::string raw;   // the values' little-endian bytes
};

// Bytes per value of a bundle array type; throws Error for an unknown type.
int bundle_type_bytes(const std::string& type);

// The bundle file of `arrays`.
std::string bundle_file(const std::vector<BundleArray>& arrays);

}  // namespace relume
