// `relume lights`: the light vector of a set of light directions, one `R G B` row per light, for
// an environment map (solid-angle integration over each light's Voronoi cell on the sphere, with
// the share of the map's energy that falls outside the light set) or for a light moved to any
// direction (interpolation weights over the captured lights).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <relume/error.hpp>
#include <relume/lighting.hpp>

#include "command_registry.hpp"
#include "core/console.hpp"
#include "options/directional_light_options.hpp"
#include "field/light_file.hpp"
#include "lighting/environment_map.hpp"
#include "options/output_paths.hpp"
#include "options/rotation_option.hpp"

namespace relume {
namespace {

struct LightsOptions {
  std::string directions;
  std::string environment;
  std::string layout = "auto";
  std::string rotate = "0";  // degrees or "auto"
  DirectionalLightOptions moved_light;
  std::string output;
  unsigned threads = 0;
};

// Lossy EXR compression (Poly Haven's DWAB maps) leaves some negative values near bright spots;
// they are integrated as they are, and said so.
std::string negative_value_note(const EnvironmentMap& map) {
  std::size_t count = 0;
  float lowest = 0;
  for (float v : map.radiance.pixels)
    if (v < 0) ++count, lowest = std::min(lowest, v);
  if (count == 0) return "";
  char text[160];
  std::snprintf(text, sizeof text,
                "\nnote: %zu negative values in the map (lowest %g), integrated as they are", count,
                lowest);
  return text;
}

// Rows on stdout (for pipes) and the summary on stderr, or the rows to the output file and the
// summary on stdout.
void write_light_vector(const LightsOptions& options, const LightRgb& rgb,
                        const std::string& summary, const std::string& header_comment) {
  if (options.output.empty()) {
    note("%s", summary.c_str());
    for (Eigen::Index i = 0; i < rgb.rows(); ++i)
      std::printf("%.9g %.9g %.9g\n", rgb(i, 0), rgb(i, 1), rgb(i, 2));
    return;
  }
  write_rgb_rows(options.output, rgb, header_comment);
  say("%s\nwrote %s", summary.c_str(), options.output.c_str());
}

void run_moved_light(const LightsOptions& options, const LightDirections& directions) {
  const LightRgb rgb = directional_light_vector(directions, options.moved_light);
  const Eigen::Vector3d direction(options.moved_light.direction.data());
  int carrying = 0;
  for (Eigen::Index i = 0; i < rgb.rows(); ++i) carrying += rgb.row(i).maxCoeff() > 0;
  char spread[64];
  std::snprintf(spread, sizeof spread, ", spread %g degrees", options.moved_light.spread_degrees);
  const std::string what = "light from " + format_direction(direction) + spread;
  write_light_vector(options, rgb,
                     what + ": " + std::to_string(carrying) + " of " +
                         std::to_string(directions.rows()) + " captured lights carry it",
                     what + ", for " + options.directions);
}

void run_lights(const LightsOptions& options) {
  check_new_output(options.output);
  const auto layout = parse_layout_option(options.layout);
  const LightDirections directions = read_light_directions(options.directions);
  if (!options.moved_light.direction.empty()) {
    run_moved_light(options, directions);
    return;
  }
  if (options.environment.empty()) throw Error("give --env MAP or --light-dir x,y,z");
  const EnvironmentMap map = load_environment_map(options.environment, layout);
  const LightVectorIntegrator integrator(map, directions, options.threads);
  const ResolvedRotation rotation = resolve_rotation(options.rotate, integrator);
  const LightVector vector = integrator.integrate(rotation.degrees);
  const std::string summary = "environment map " + map.name + " (" + layout_name(map.layout) +
                              ", " + std::to_string(map.radiance.width) + "x" +
                              std::to_string(map.radiance.height) + "), " +
                              std::to_string(directions.rows()) +
                              " lights: " + rotation.information + negative_value_note(map);
  write_light_vector(options, vector.rgb, summary,
                     "light vector of " + map.name + " for " + options.directions + ", rotated " +
                         std::to_string(rotation.degrees) + " degrees about +y");
}

const CommandRegistration registration{
    25, [](CLI::App& app) {
      auto options = std::make_shared<LightsOptions>();
      auto* command = app.add_subcommand(
          "lights",
          "Sample an environment map onto light directions: each light gets the radiance x solid "
          "angle of its Voronoi cell on the sphere; directions farther from every light than the "
          "light set's median spacing count as outside and are reported, not used. Or, with "
          "--light-dir, the weights of a light moved to any direction (spherical barycentric on "
          "the triangulated light set).\n"
          "Example: relume lights --dirs scene --light-dir 1,0,0.3 --light-color 1,0.9,0.8");
      command
          ->add_option("--dirs", options->directions,
                       "Light directions: a plain 'x y z' file, an RTI .lp file or a field folder "
                       "(camera frame: x right, y up, z towards the camera)")
          ->required();
      auto* env =
          command->add_option("--env", options->environment,
                              "Environment map, any format OpenImageIO reads (.hdr, .exr, ...)");
      auto* direction = add_light_direction_option(*command, options->moved_light);
      env->excludes(direction);
      direction->excludes(env);
      add_light_color_options(*command, options->moved_light, direction);
      command
          ->add_option("--layout", options->layout,
                       "Map layout: auto (2:1 latlong, 1:1 angular, 3:4 vertical cross), latlong, "
                       "angular or cross")
          ->capture_default_str()
          ->needs(env);
      add_rotation_option(*command, options->rotate,
                          "Rotate the environment about the up axis (+y) by this many degrees, "
                          "counter-clockwise seen from above (+90 brings light from +x to -z)")
          ->needs(env);
      command->add_option(
          "-o,--output", options->output,
          "Write the rows here (atomically) and the summary to stdout; default: rows "
          "to stdout, summary to stderr");
      command->add_option("--threads", options->threads, "Worker threads (default: all cores)");
      command->callback([options] { run_lights(*options); });
    }};

}  // namespace
}  // namespace relume
