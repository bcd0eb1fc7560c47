// Implementation of the 8-bit sRGB table (srgb_codes.hpp).
#include "image/srgb_codes.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <relume/image.hpp>

namespace relume {
namespace {

constexpr int bins = 8192;

// What write_image stores for linear value v: the curve, then OpenImageIO's conversion.
int stored_code(float v) {
  const float encoded = linear_to_srgb(v);
  std::uint8_t code = 0;
  OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, &encoded, OIIO::TypeDesc::UINT8, &code, 1);
  return code;
}

struct SrgbTable {
  std::array<std::uint8_t, bins + 1> base{};
  std::array<float, bins + 1> step{};  // where base + 1 begins within the bin (infinity: nowhere)
  // threshold[k]: the smallest float in [0, 1] whose code is at least k (bisection over the bit
  // patterns, which order non-negative floats); threshold[256] is infinity.
  std::array<float, 257> threshold{};

  SrgbTable() {
    threshold[256] = std::numeric_limits<float>::infinity();
    for (int k = 1; k < 256; ++k) {
      std::uint32_t low = 0, high = std::bit_cast<std::uint32_t>(1.0f);
      while (low < high) {
        const std::uint32_t middle = low + (high - low) / 2;
        if (stored_code(std::bit_cast<float>(middle)) >= k)
          high = middle;
        else
          low = middle + 1;
      }
      threshold[k] = std::bit_cast<float>(low);
    }
    for (int b = 0; b <= bins; ++b) {
      const float start = float(b) / bins, end = float(b + 1) / bins;
      base[b] = std::uint8_t(stored_code(start));
      const float next = threshold[std::min(256, base[b] + 1)];
      step[b] = next < end ? next : std::numeric_limits<float>::infinity();
    }
  }
};

const SrgbTable& srgb_table() {
  static const SrgbTable table;
  return table;
}

}  // namespace

float unit_clamped(float v) { return v > 0 ? std::min(v, 1.0f) : 0.0f; }

std::uint8_t srgb_code(float linear) {
  const SrgbTable& table = srgb_table();
  const float v = unit_clamped(linear);
  const int bin = int(v * bins);
  return std::uint8_t(table.base[bin] + (v >= table.step[bin]));
}

const std::array<float, 256>& srgb_code_thresholds() {
  static const std::array<float, 256> thresholds = [] {
    std::array<float, 256> first{};
    std::copy_n(srgb_table().threshold.begin(), 256, first.begin());
    return first;
  }();
  return thresholds;
}

}  // namespace relume
