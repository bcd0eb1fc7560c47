// A CompressedField of a chosen shape filled with seeded random values, for the relighting tests
// and for `relume bench` when it is given no container. Same seed, same field.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>

namespace relume {

struct RandomFieldShape {
  int width = 640;
  int height = 640;
  int channels = 3;
  int lights = 253;
  int clusters = 128;
  int terms = 4;
  int residual_per_function = 12;  // residual entries per stored row (at most `lights`)
  // Rows get a uniformly random entry count in [0, residual_per_function] instead (empty rows
  // included), as a thresholded residual has.
  bool vary_residual = false;
  double stored_fraction = 1.0;  // share of functions that are stored; the rest relight to 0
  std::uint64_t seed = 1;
};

// Weights in [-1, 1], bases in [0, 1], residual values normal with sigma 0.1 sorted by |value|
// descending with distinct lights per row, identity basis. Throws Error for a shape that cannot
// be built (non-positive sizes, more residual entries than lights, fraction outside [0, 1]).
CompressedField random_compressed_field(const RandomFieldShape& shape);

// A light vector (lights x RGB) with entries in [0, 1].
LightRgb random_light_vector(int lights, std::uint64_t seed);

}  // namespace relume
