// relume.light_vector (an environment map integrated over the lights' cells on the sphere, at one
// or many rotations, or a light moved between the captured ones, from one or many directions) and
// relume.sky (the built-in HDR sky).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>
#include <relume/lighting.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "lighting/environment_map.hpp"
#include "lighting/light_interpolation.hpp"
#include "moved_light.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

bool is_path(py::handle object) {
  return py::isinstance<py::str>(object) ||
         py::isinstance(object, py::module_::import("os").attr("PathLike"));
}

EnvironmentMap environment_from(py::handle env, const std::optional<EnvironmentLayout>& layout) {
  if (is_path(env)) {
    const auto path = env.cast<std::filesystem::path>();
    return with_file_errors([&] {
      py::gil_scoped_release released;
      return load_environment_map(path, layout);
    });
  }
  Image radiance = image_from(env, "env");
  const std::string name = "the env array";
  const EnvironmentLayout chosen =
      layout ? *layout : detect_layout(radiance.width, radiance.height, name);
  return make_environment_map(std::move(radiance), chosen, name);
}

py::array stacked(const std::vector<LightRgb>& vectors, py::ssize_t lights) {
  std::vector<float> rows;
  rows.reserve(vectors.size() * static_cast<std::size_t>(lights) * 3);
  for (const LightRgb& rgb : vectors) rows.insert(rows.end(), rgb.data(), rgb.data() + rgb.size());
  return adopt_vector(std::move(rows), {static_cast<py::ssize_t>(vectors.size()), lights, 3});
}

// The light vector of an environment map at each angle of `rotate` (a number: one).
std::vector<LightRgb> environment_light_vectors(py::handle env, const LightDirections& directions,
                                                py::handle rotate, const std::string& layout,
                                                unsigned threads, bool& several) {
  const EnvironmentMap map = environment_from(env, parse_layout_option(layout));
  const py::array given = py::array::ensure(rotate);
  several = given && given.ndim() == 1;
  const DoubleArray degrees = finite_float64(
      several ? checked_array(rotate, "rotate", Accepted::real_numbers, {-1}, "(count,)")
              : checked_array(rotate, "rotate", Accepted::real_numbers, {},
                              "a number or a sequence of numbers"),
      "rotate");
  std::vector<LightRgb> vectors;
  py::gil_scoped_release released;
  const LightVectorIntegrator integrator(map, directions, threads);
  for (py::ssize_t n = 0; n < degrees.size(); ++n)
    vectors.push_back(integrator.integrate(degrees.data()[n]).rgb);
  return vectors;
}

}  // namespace

void bind_lighting(py::module_& module) {
  module.def(
      "light_vector",
      [](py::handle dirs, py::handle env, py::handle light_dir, py::handle color, double spread,
         py::handle rotate, const std::string& layout, unsigned threads) {
        const LightDirections directions = directions_from(dirs, "dirs");
        if (env.is_none() == light_dir.is_none())
          throw Error(
              "give the light: env (an environment map) or light_dir= (a moved light), one of "
              "the two");
        const MovedLight moved = moved_light_from(light_dir, color, spread, true);
        bool several = moved.several;
        const std::vector<LightRgb> vectors =
            moved.directions.empty()
                ? environment_light_vectors(env, directions, rotate, layout, threads, several)
                : moved_light_vectors(moved, directions);
        const py::array all = stacked(vectors, directions.rows());
        return several ? py::object(all) : all.attr("reshape")(directions.rows(), 3);
      },
      "dirs"_a, "env"_a = py::none(), py::kw_only(), "light_dir"_a = py::none(),
      "color"_a = default_light_color(), "spread"_a = DirectionalLight{}.spread_degrees,
      "rotate"_a = 0.0, "layout"_a = "auto", "threads"_a = 0,
      R"(The light vector of an environment map or of a moved light for a set of light
directions: float32 (lights, 3), RGB per light (as `relume lights` writes it).

Environment map (env): each light receives the map's radiance x solid angle over its Voronoi
cell on the sphere (the directions nearer to it than to any other light); directions farther
than the set's typical spacing from every light belong to none (DiLiGenT's frontal lights
miss about half of a map). env: a map file (lat-long, mirror-ball or vertical cross, any
format OpenImageIO reads) or an array (height, width) or (height, width, channels) of linear
radiance. layout: "auto" (from the aspect ratio: 2:1 lat-long, 1:1 angular, 3:4 cross),
"latlong", "angular" or "cross". rotate: degrees about the up axis (+y), or a sequence of
angles for (count, lights, 3), the map's pixels sampled once for all of them.

Moved light (light_dir=, as `relume relight --light-dir`): a directional light from (x, y, z)
(camera frame: x right, y up, z towards the camera; need not be unit), interpolated between
the captured lights by spherical barycentric weights (non-negative, summing to one; at a
captured direction that light alone); a direction outside the captured lights' cover is lit
from the nearest point of its rim, with a warning. (count, 3) directions give (count, lights,
3). color: r, g, b of the light (1, 1, 1 = one captured light's). spread: angular radius in
degrees, 0 to 90 (0: a point light; larger: a softer disc light).)");

  module.def(
      "sky",
      [](int width, double sun_elevation, double sun_azimuth, double sun_radiance,
         double sun_radius) {
        if (width < 2 || width % 2 != 0)
          throw Error("sky width must be an even number >= 2, got " + std::to_string(width));
        SkyOptions options;
        options.width = width;
        options.sun_elevation_deg = sun_elevation;
        options.sun_azimuth_deg = sun_azimuth;
        options.sun_radiance = sun_radiance;
        options.sun_radius_deg = sun_radius;
        return adopt_image(render_sky(options));
      },
      py::kw_only(), "width"_a = SkyOptions{}.width,
      "sun_elevation"_a = SkyOptions{}.sun_elevation_deg,
      "sun_azimuth"_a = SkyOptions{}.sun_azimuth_deg, "sun_radiance"_a = SkyOptions{}.sun_radiance,
      "sun_radius"_a = SkyOptions{}.sun_radius_deg,
      R"(The built-in HDR sky as a lat-long float32 array (width / 2, width, 3): a blue
gradient, a warm darker ground and a small bright sun (elevation and azimuth in degrees,
azimuth about +y from straight ahead towards +x). Handy for relighting without a map file.)");
}

}  // namespace relume::python
