// Implementation of the shared --lights / --env options.
#include "light_source_options.hpp"

#include <cstdio>
#include <relume/error.hpp>
#include <relume/lighting.hpp>

#include "core/console.hpp"
#include "field/light_file.hpp"
#include "lighting/environment_map.hpp"

namespace relume {

void add_light_source_options(CLI::App& command, LightSourceOptions& options) {
  auto* lights = command.add_option("--lights", options.lights_file,
                                    "Light vector file: one 'R G B' row per light, in the light "
                                    "order of the input (as written by `relume lights`)");
  auto* env = command.add_option("--env", options.environment,
                                 "Environment map (lat-long, mirror ball or vertical cross; any "
                                 "format OpenImageIO reads)");
  lights->excludes(env);
  env->excludes(lights);
  command
      .add_option("--layout", options.layout,
                  "Environment map layout: auto (from the aspect ratio), latlong, angular, cross")
      ->capture_default_str();
  command
      .add_option("--rotate", options.rotate_degrees,
                  "Rotate the environment about the up axis (+y) by this many degrees")
      ->capture_default_str();
}

LightRgb resolve_light_vector(const LightSourceOptions& options,
                              const LightDirections& directions) {
  if (options.lights_file.empty() && options.environment.empty())
    throw Error("give the light source: --lights FILE or --env MAP");
  if (!options.environment.empty()) {
    const EnvironmentMap map =
        load_environment_map(options.environment, parse_layout_option(options.layout));
    LightVector vector = integrate_light_vector(map, directions, options.rotate_degrees);
    note("%s: %s", options.environment.c_str(), describe_coverage(vector).c_str());
    return vector.rgb;
  }
  LightRgb lights = read_rgb_rows(options.lights_file, "light vector");
  if (lights.rows() != directions.rows())
    throw Error(options.lights_file + " has " + std::to_string(lights.rows()) +
                " rows but the input has " + std::to_string(directions.rows()) + " lights");
  return lights;
}

}  // namespace relume
