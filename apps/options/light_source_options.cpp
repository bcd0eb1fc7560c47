// Implementation of the shared --lights / --env / --light-dir options.
#include "options/light_source_options.hpp"

#include <cstdio>
#include <relume/error.hpp>
#include <relume/lighting.hpp>

#include "core/console.hpp"
#include "field/light_file.hpp"
#include "lighting/environment_map.hpp"
#include "options/rotation_option.hpp"

namespace relume {

void add_light_source_options(CLI::App& command, LightSourceOptions& options) {
  auto* lights = command.add_option("--lights", options.lights_file,
                                    "Light vector file: one 'R G B' row per light, in the light "
                                    "order of the input (as written by `relume lights`)");
  auto* env = command.add_option("--env", options.environment,
                                 "Environment map (lat-long, mirror ball or vertical cross; any "
                                 "format OpenImageIO reads)");
  auto* direction = add_light_direction_option(command, options.moved_light);
  lights->excludes(env)->excludes(direction);
  env->excludes(lights)->excludes(direction);
  direction->excludes(lights)->excludes(env);
  add_light_color_options(command, options.moved_light, direction);
  command
      .add_option("--layout", options.layout,
                  "Environment map layout: auto (from the aspect ratio), latlong, angular, cross")
      ->capture_default_str()
      ->needs(env);
  add_rotation_option(command, options.rotate,
                      "Rotate the environment about the up axis (+y) by this many degrees")
      ->needs(env);
}

LightRgb resolve_light_vector(const LightSourceOptions& options,
                              const LightDirections& directions) {
  if (!options.moved_light.direction.empty())
    return directional_light_vector(directions, options.moved_light);
  if (options.lights_file.empty() && options.environment.empty())
    throw Error("give the light source: --lights FILE, --env MAP or --light-dir x,y,z");
  if (!options.environment.empty()) {
    const EnvironmentMap map =
        load_environment_map(options.environment, parse_layout_option(options.layout));
    const LightVectorIntegrator integrator(map, directions);
    const ResolvedRotation rotation = resolve_rotation(options.rotate, integrator);
    note("%s: %s", options.environment.c_str(), rotation.information.c_str());
    return integrator.integrate(rotation.degrees).rgb;
  }
  LightRgb lights = read_rgb_rows(options.lights_file, "light vector");
  if (lights.rows() != directions.rows())
    throw Error(options.lights_file + " has " + std::to_string(lights.rows()) +
                " rows but the input has " + std::to_string(directions.rows()) + " lights");
  return lights;
}

}  // namespace relume
