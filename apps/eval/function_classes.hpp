// The two subsets `relume eval` reports besides all functions (paper Fig. 4 a-c): mostly diffuse
// and mostly specular or shadowed. A reflectance function is "diffuse" when the best fit
// a + b . l over the light directions l, the exact form of an unshadowed Lambertian function plus
// a constant (ambient, interreflection), leaves at most `threshold` of its energy; otherwise it is
// "specular/shadowed": highlights, attached and cast shadows are what such a fit cannot follow.
#pragma once

#include <cstdint>
#include <relume/field.hpp>
#include <vector>

namespace relume {

struct FunctionClasses {
  double threshold = 0;
  std::vector<float> linear_residual;  // per stored row: energy fraction the fit leaves
  std::vector<std::uint8_t> diffuse;   // per stored row: 1 = diffuse, 0 = specular/shadowed
  std::size_t diffuse_count = 0;
};

// For the functions `stored_function` of `field` (their values in the light basis). Throws Error
// for a threshold outside [0, 1] or fewer than 5 lights (the fit has 4 unknowns).
FunctionClasses classify_functions(const ReflectanceField& field,
                                   const std::vector<std::uint32_t>& stored_function,
                                   double threshold, unsigned threads);

}  // namespace relume
