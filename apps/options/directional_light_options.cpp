// Implementation of the shared moved-light options.
#include "options/directional_light_options.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "core/console.hpp"

namespace relume {

CLI::Option* add_light_direction_option(CLI::App& command, DirectionalLightOptions& options) {
  return command
      .add_option("--light-dir", options.direction,
                  "Move a light: a directional light from x,y,z (camera frame: x right, y up, z "
                  "towards the camera; need not be unit), interpolated between the captured "
                  "lights by spherical barycentric weights; e.g. --light-dir 0.5,0.3,0.8")
      ->delimiter(',')
      ->expected(3);
}

void add_light_color_options(CLI::App& command, DirectionalLightOptions& options,
                             CLI::Option* direction) {
  CLI::Option* color =
      command
          .add_option("--light-color", options.color,
                  "Colour and intensity of the moved light, r,g,b (1,1,1 = one captured light)")
          ->delimiter(',')
          ->expected(3)
          ->capture_default_str();
  CLI::Option* spread =
      command
          .add_option("--spread", options.spread_degrees,
                      "Angular radius of the moved light in degrees (0 = a point light; larger "
                      "is a softer disc light)")
          ->check(CLI::Range(0.0, 90.0))
          ->capture_default_str();
  if (direction) {
    color->needs(direction);
    spread->needs(direction);
  }
}

std::string format_direction(const Eigen::Vector3d& d) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g)", d.x(), d.y(), d.z());
  return text;
}

LightRgb directional_light_vector(const LightInterpolation& interpolation,
                                  const DirectionalLightOptions& options,
                                  const Eigen::Vector3d& direction) {
  const DirectionalLight light{direction, Eigen::Vector3d(options.color.data()),
                               options.spread_degrees};
  const LightRgb rgb = interpolation.light_vector(light);
  if (!interpolation.covers(direction))
    note(
        "light from %s lies outside the captured lights' cover: lit from the nearest point of "
        "its rim",
        format_direction(direction).c_str());
  if (verbosity() == Verbosity::verbose) {
    const Eigen::VectorXd w = interpolation.weights(direction, options.spread_degrees);
    std::vector<int> order(w.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return w[a] > w[b]; });
    std::string carried;
    for (std::size_t k = 0; k < std::min<std::size_t>(order.size(), 6) && w[order[k]] > 0; ++k)
      carried += " " + std::to_string(order[k] + 1) + ":" + std::to_string(w[order[k]]);
    detail("light from %s: weights (light:weight)%s", format_direction(direction).c_str(),
           carried.c_str());
  }
  return rgb;
}

LightRgb directional_light_vector(const LightDirections& directions,
                                  const DirectionalLightOptions& options) {
  return directional_light_vector(LightInterpolation(directions), options,
                                  Eigen::Vector3d(options.direction.data()));
}

}  // namespace relume
