// Implementation of the moved light's arguments (moved_light.hpp).
#include "moved_light.hpp"

#include <relume/error.hpp>
#include <string>

#include "arrays.hpp"
#include "lighting/light_interpolation.hpp"

namespace relume::python {

py::tuple default_light_color() {
  const Eigen::Vector3d rgb = DirectionalLight{}.rgb;
  return py::make_tuple(rgb.x(), rgb.y(), rgb.z());
}

MovedLight moved_light_from(py::handle light_dir, py::handle color, double spread,
                            bool several_allowed) {
  MovedLight light;
  const DoubleArray rgb = finite_float64(
      checked_array(color, "color", Accepted::real_numbers, {3}, "(3,): r, g, b"), "color");
  light.rgb = Eigen::Vector3d(rgb.at(0), rgb.at(1), rgb.at(2));
  light.spread_degrees = spread;
  if (light_dir.is_none()) {
    const DirectionalLight defaults;
    if (light.rgb != defaults.rgb || spread != defaults.spread_degrees)
      throw Error("color= and spread= shape a moved light: give light_dir= (x, y, z) too");
    return light;
  }
  const py::array given = py::array::ensure(light_dir);
  light.several = several_allowed && given && given.ndim() == 2;
  const DoubleArray rows = finite_float64(
      light.several
          ? checked_array(light_dir, "light_dir", Accepted::real_numbers, {-1, 3}, "(count, 3)")
          : checked_array(light_dir, "light_dir", Accepted::real_numbers, {3},
                          several_allowed ? "(3,): x, y, z, or (count, 3)" : "(3,): x, y, z"),
      "light_dir");
  const py::ssize_t count = light.several ? rows.shape(0) : 1;
  for (py::ssize_t n = 0; n < count; ++n) {
    const double* row = rows.data() + 3 * n;
    light.directions.emplace_back(row[0], row[1], row[2]);
  }
  return light;
}

std::vector<LightRgb> moved_light_vectors(const MovedLight& light,
                                          const LightDirections& directions) {
  std::vector<LightRgb> vectors;
  std::size_t outside = 0;
  {
    py::gil_scoped_release released;
    const LightInterpolation interpolation(directions);
    for (const Eigen::Vector3d& direction : light.directions) {
      vectors.push_back(
          interpolation.light_vector(DirectionalLight{direction, light.rgb, light.spread_degrees}));
      outside += !interpolation.covers(direction);
    }
  }
  if (outside > 0)
    py::module_::import("warnings")
        .attr("warn")(std::to_string(outside) + " of " + std::to_string(light.directions.size()) +
                      " light directions lie outside the captured lights' cover: lit from the "
                      "nearest point of its rim");
  return vectors;
}

LightRgb relight_light(py::handle light, py::handle light_dir, py::handle color, double spread,
                       const LightDirections& directions) {
  if (light.is_none() == light_dir.is_none())
    throw Error(
        "give the light: a light vector (lights, 3) or light_dir= (x, y, z), one of the two");
  const MovedLight moved = moved_light_from(light_dir, color, spread, false);
  if (moved.directions.empty()) return rgb_rows_from(light, "light", directions.rows());
  return moved_light_vectors(moved, directions).front();
}

}  // namespace relume::python
