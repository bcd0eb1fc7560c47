// A light moved to any direction between the captured ones, as `relume relight --light-dir`
// (with --light-color and --spread) has it: the light_dir=, color= and spread= arguments of
// relume.light_vector and of Field.relight and Compressed.relight, turned into light vectors by
// lighting/light_interpolation.hpp, the code behind the command's options, with DirectionalLight's
// defaults, which the command's options take too.
#pragma once

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <relume/field.hpp>
#include <vector>

namespace relume::python {

namespace py = pybind11;

struct MovedLight {
  std::vector<Eigen::Vector3d> directions;  // empty: no light_dir given
  bool several = false;                     // light_dir was (count, 3)
  Eigen::Vector3d rgb;
  double spread_degrees = 0;
};

// DirectionalLight's colour, (r, g, b), as the default of color=.
py::tuple default_light_color();

// light_dir (None, (3,) or, where `several_allowed`, (count, 3)), color (3,) and spread
// (degrees). Throws Error for arrays of other shapes or values that are not finite, and for a
// color or spread other than the defaults without a light_dir (they shape a moved light only).
MovedLight moved_light_from(py::handle light_dir, py::handle color, double spread,
                            bool several_allowed);

// The light vector (lights, 3) of each of `light`'s directions for the captured `directions`.
// Warns (Python's warnings) when a direction lies outside the captured lights' cover: it is lit
// from the nearest point of the cover's rim. Throws Error for a light set that cannot be
// triangulated, a zero direction, a negative colour or a spread outside [0, 90].
std::vector<LightRgb> moved_light_vectors(const MovedLight& light,
                                          const LightDirections& directions);

// What relight(light, light_dir=..., color=..., spread=...) lights with: the light vector
// `light` (lights, 3) or the moved light from light_dir (x, y, z), exactly one of the two.
LightRgb relight_light(py::handle light, py::handle light_dir, py::handle color, double spread,
                       const LightDirections& directions);

}  // namespace relume::python
