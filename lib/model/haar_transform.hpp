// Orthonormal Haar wavelet transform of a strided sequence, in place, for any length. It is the
// basis transform applied to reflectance functions (over the lights) and to light vectors: being
// orthonormal, <H r, H I> = <r, I>, so a field compressed in the Haar domain is relit with the
// Haar-transformed light vector.
//
// One level on n values turns each pair (x[2k], x[2k+1]) into the average
// s = (x[2k] + x[2k+1]) / sqrt(2) and the detail d = (x[2k] - x[2k+1]) / sqrt(2). When n is odd the
// last value has no partner and is carried unchanged to the next level as its last average. The
// level writes its ceil(n/2) averages to the front of the sequence and its floor(n/2) details
// after them; the next level repeats on the averages until one value is left (the overall sum
// scaled by 2^(-levels/2)). Every level is an orthogonal map, so the whole transform is.
#pragma once

namespace relume {

// values[0], values[stride], ..., values[(count - 1) * stride] are transformed in place.
void haar_forward(float* values, int count, int stride);
void haar_inverse(float* values, int count, int stride);

}  // namespace relume
