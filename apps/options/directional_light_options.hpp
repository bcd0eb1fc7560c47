// The options of a moved light, shared by `relight`, `lights` and `relight-sequence`:
// `--light-color r,g,b` and `--spread DEG` (and, where one direction is meant, `--light-dir
// x,y,z`), resolved to a light vector by lighting/light_interpolation.hpp.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <relume/field.hpp>
#include <string>
#include <vector>

#include "lighting/light_interpolation.hpp"

namespace relume {

// The defaults are DirectionalLight's, which the Python module offers too.
struct DirectionalLightOptions {
  std::vector<double> direction;  // empty: not given
  std::vector<double> color = [] {
    const Eigen::Vector3d rgb = DirectionalLight{}.rgb;
    return std::vector<double>(rgb.data(), rgb.data() + 3);
  }();
  double spread_degrees = DirectionalLight{}.spread_degrees;
};

// Adds --light-dir; returns it so callers can make it exclusive with other light sources.
CLI::Option* add_light_direction_option(CLI::App& command, DirectionalLightOptions& options);
// Adds --light-color and --spread; with `direction` (the --light-dir option), both are usage
// errors without it instead of being ignored.
void add_light_color_options(CLI::App& command, DirectionalLightOptions& options,
                             CLI::Option* direction = nullptr);

// The light vector of a light from `direction` with the options' colour and spread. Notes a
// direction outside the captured cover (it is lit from the nearest point of the cover's rim)
// and, when verbose, the lights that carry the weight.
LightRgb directional_light_vector(const LightInterpolation& interpolation,
                                  const DirectionalLightOptions& options,
                                  const Eigen::Vector3d& direction);

// The same for the options' own --light-dir.
LightRgb directional_light_vector(const LightDirections& directions,
                                  const DirectionalLightOptions& options);

// "(x, y, z)" for messages.
std::string format_direction(const Eigen::Vector3d& direction);

}  // namespace relume
