// The weights W of a compressed field seen in the camera domain: for each term j and colour
// component a, one width x height image of the weights of every pixel. With three channels the
// components are an orthonormal colour transform of the channels' weights (luma (R+G+B)/sqrt 3,
// (R-G)/sqrt 2, (R+G-2B)/sqrt 6): the channels' weights are strongly correlated, and an
// orthonormal transform keeps a weight error's cost in squared error whatever plane it lands in.
// Other channel counts keep the channels as they are. Functions without a stored row are 0 in
// the planes and ignored on the way back. The container codes these planes as a JPEG 2000
// codestream (container/weight_plane_coding.hpp).
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// channels * terms planes of width * height values, plane a * terms + j after plane
// a * terms + j - 1, each row-major.
std::vector<float> weight_planes(const CompressedField& field);

// Sets every stored row's weights from integer planes of one step, laid out as weight_planes lays
// them out: plane value i is float(samples[i] x step), as a JPEG 2000 codestream of the planes
// decodes (container/weight_plane_coding.hpp). Throws Error when the planes do not have the
// field's size.
void set_weights_from_integer_planes(CompressedField& field,
                                     const std::vector<std::int32_t>& samples, float step);

}  // namespace relume
