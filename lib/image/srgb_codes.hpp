// 8-bit sRGB codes of linear values by table, as write_image stores integer outputs: the code of
// a linear value v in [0, 1] is OpenImageIO's float-to-8-bit conversion of linear_to_srgb(v).
// Evaluating that curve costs a pow per value, most of the time an 8-bit encode of a viewer frame
// took (docs/viewer.md); the table gives the same code from a bin lookup and one comparison. It is
// built once from the curve itself: the 255 thresholds where the code steps up (found by bisection
// over the floats, the curve being non-decreasing) and, for each of 8192 bins of [0, 1], the code
// at its start and the one threshold it may hold (codes are at least 1 / (255 x 12.92) apart, wider
// than a bin).
#pragma once

#include <array>
#include <cstdint>

namespace relume {

// `v` clamped to [0, 1], NaN to 0 (std::clamp keeps NaN, which no table may be indexed with):
// what an exposed pixel is before it is encoded.
float unit_clamped(float v);

// The code of linear_to_srgb(v) in 8 bits; v is unit_clamped first (NaN and -Inf: 0, +Inf: 255).
std::uint8_t srgb_code(float linear);

// The 255 thresholds of those codes: entry k (1..255) is the smallest float whose code is at
// least k; entry 0 is 0. A renderer outside C++ (the published web page's shader) finds a
// value's code as the number of entries 1..255 at or below it, the same code as srgb_code.
const std::array<float, 256>& srgb_code_thresholds();

}  // namespace relume
