// The luminance of a linear pixel: Rec. 709 weights of its first three channels (a grey image:
// its one channel). Shared by the automatic exposure and the image comparisons.
#pragma once

namespace relume {

inline float luminance(const float* pixel, int channels) {
  return channels >= 3 ? 0.2126f * pixel[0] + 0.7152f * pixel[1] + 0.0722f * pixel[2] : pixel[0];
}

}  // namespace relume
