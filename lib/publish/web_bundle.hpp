// The published page's binary files ("bundles"): a few arrays in one file, each coded as the
// container codes its sections (container/section_coding.hpp: raw, or zstd after a byte shuffle
// or a delta then shuffle, whichever is smallest), which the page undoes in JavaScript
// (web/field_data.js, with the vendored zstd decoder web/fzstd.js).
//
// File: "RLWB", then little-endian uint32s: the version (1), the number of arrays n, and per
// array its coding word (SectionCoding::word), its coded bytes and its raw bytes; then the
// arrays' coded bytes one after the other. What each array is (its name and element type) the
// manifest says, in the same order.
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
