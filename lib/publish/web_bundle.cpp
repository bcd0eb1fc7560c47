// Implementation of the published page's bundle files (web_bundle.hpp).
#include "publish/web_bundle.hpp"

#include <zlib.h>

#include <cstdint>
#include <relume/error.hpp>

#include "container/section_coding.hpp"

namespace relume {
namespace {

constexpr std::uint32_t deflate_codec = 2;

void append_uint32(std::string& out, std::uint32_t value) {
  for (int b = 0; b < 4; ++b, value >>= 8) out.push_back(char(value & 0xFF));
}

std::uint32_t checked_uint32(std::size_t size, const std::string& name) {
  if (size > 0xFFFFFFFFu)
    throw Error("the published array " + name + " has " + std::to_string(size) +
                " bytes, more than a bundle's 4 GiB");
  return std::uint32_t(size);
}

// Raw deflate (no zlib or gzip header) at the best compression.
std::string deflate_raw(const std::string& bytes, const std::string& name) {
  z_stream stream{};
  if (deflateInit2(&stream, Z_BEST_COMPRESSION, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error("zlib cannot start compressing the published array " + name);
  std::string out(deflateBound(&stream, uLong(bytes.size())), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = uInt(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = uInt(out.size());
  const int result = deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  if (result != Z_STREAM_END) throw Error("zlib cannot compress the published array " + name);
  return out;
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
    const int element_bytes = bundle_type_bytes(array.type);
    std::string best = array.raw;
    std::uint32_t word = 0;
    for (SectionFilter filter : candidate_filters(element_bytes)) {
      std::string coded = deflate_raw(filtered_bytes(array.raw, filter, element_bytes), array.name);
      if (coded.size() < best.size()) {
        best = std::move(coded);
        word = deflate_codec | (std::uint32_t(filter) << 8) | (std::uint32_t(element_bytes) << 16);
      }
    }
    append_uint32(header, word);
    append_uint32(header, checked_uint32(best.size(), array.name));
    append_uint32(header, checked_uint32(array.raw.size(), array.name));
    body += best;
  }
  return header + body;
}

}  // namespace relume
