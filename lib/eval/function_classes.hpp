// The two subsets `relume eval` reports besides all functions (paper Fig. 4 a-c): mostly diffuse
// and mostly specular or shadowed. A reflectance function is "diffuse" when a clamped linear fit
// max(0, a + b . l) over the light directions l, the form of a Lambertian function with its
// attached shadow plus a constant (ambient, interreflection), leaves at most `threshold` of its
// energy; otherwise it is "specular/shadowed": highlights and cast shadows are what such a fit
// cannot follow. a and b are fitted in least squares over the lit lights (values above
// lit_fraction of the function's largest), so that the clamp serves hemispheres and full spheres
// of lights alike.
#pragma once

#include <cstdint>
#include <relume/field.hpp>
#include <vector>

namespace relume {

struct FunctionClasses {
  double threshold = 0;
  std::vector<std::uint8_t> diffuse;  // per stored row: 1 = diffuse, 0 = specular/shadowed
  std::size_t diffuse_count = 0;
};

// Lights with values above this fraction of a function's largest value are its lit lights.
constexpr double lit_fraction = 0.05;

// For the functions `stored_function` of `field` (their values in the light basis). Throws Error
// for a threshold outside [0, 1] or fewer than 5 lights (the fit has 4 unknowns). A function with
// fewer than 5 lit lights is specular/shadowed.
FunctionClasses classify_functions(const ReflectanceField& field,
                                   const std::vector<std::uint32_t>& stored_function,
                                   double threshold, unsigned threads);

}  // namespace relume
