// The weights W of a compressed field seen in the camera domain: for each term j and colour
// component a, one width x height image of the weights of every pixel. With three channels the
// components are an orthonormal colour transform of the channels' weights: the channels' weights
// are strongly correlated, and an orthonormal transform keeps a weight error's cost in squared
// error whatever plane it lands in. Each term has its own (field.coded_weights.colour_angles):
// the principal axes of its three channels' weights, so that nearly all of a term lands in its
// first component (a diffuse term carries the object's colour, a specular one the light's);
// without angles, every term has luma (R+G+B)/sqrt 3, (R-G)/sqrt 2, (R+G-2B)/sqrt 6. Other
// channel counts keep the channels as they are. Functions without a stored row are 0 in
// the planes and ignored on the way back. The container codes these planes as a JPEG 2000
// codestream (container/weight_plane_coding.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// Term j's colour transform from its angles (a, b, c) = colour_angles[3j ...] in units of
// pi / 32767: the rotation Rz(a) Ry(b) Rx(c), row k component k's entry for each channel.
std::array<std::array<double, 3>, 3> colour_rotation(const std::int16_t* angles);

// For a field of three channels, each term's principal colour axes (the eigenvectors of its
// channels' weights' 3 x 3 second moments over the stored pixels, strongest first) as angles for
// colour_angles; empty for other channel counts.
std::vector<std::int16_t> principal_colour_angles(const CompressedField& field);

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
