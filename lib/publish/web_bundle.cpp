// Implementation of the published page's bundle files (web_bundle.hpp).
#include "publish/web_bundle.hpp"

#include <cstdint>
#include <relume/error.hpp>

#include "container/section_coding.hpp"

namespace relume {
namespace {

void append_uint32(std::string& out, std::uint32_t value) {
  for (int b = 0; b < 4; ++b, value >>= 8) out.push_back(char(value & 0xFF));
}

std::uint32_t checked_uint32(std::size_t size, const std::string& name) {
  if (size > 0xFFFFFFFFu)
    throw Error("the published array " + name + " has " + std::to_string(size) +
                " bytes, more than a bundle's 4 GiB");
  return std::uint32_t(size);
}

}  // namespace

int bundle_type_bytes(const std::string& type) {
  if (type == "uint8") return 1;
  if (type == "uint16" || type == "int16" || type == "med16") return 2;
  if (type == "uint32" || type == "float32") return 4;
  throw Error("unknown published array type '" + type + "'");
}

std::string bundle_file(const std::vector<BundleArray>& arrays) {
  std::string header = "RLWB", body;
  append_uint32(header, 1);
  append_uint32(header, std::uint32_t(arrays.size()));
  for (const BundleArray& array : arrays) {
    const CodedSection coded = code_section(array.raw, bundle_type_bytes(array.type));
    append_uint32(header, coded.coding.word());
    append_uint32(header, checked_uint32(coded.bytes.size(), array.name));
    append_uint32(header, checked_uint32(array.raw.size(), array.name));
    body += coded.bytes;
  }
  return header + body;
}

}  // namespace relume
