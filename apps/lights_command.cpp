// `relume lights`: samples an environment map onto a set of light directions (solid-angle
// integration over each light's Voronoi cell on the sphere) and writes the light vector, one
// `R G B` row per light, with the share of the map's energy that falls outside the light set.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <relume/lighting.hpp>

#include "command_registry.hpp"
#include "core/console.hpp"
#include "field/light_file.hpp"
#include "lighting/environment_map.hpp"

namespace relume {
namespace {

struct LightsOptions {
  std::string directions;
  std::string environment;
  std::string layout = "auto";
  double rotate_degrees = 0;
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

void run_lights(const LightsOptions& options) {
  const auto layout = parse_layout_option(options.layout);
  const LightDirections directions = read_light_directions(options.directions);
  const EnvironmentMap map = load_environment_map(options.environment, layout);
  const LightVector vector =
      integrate_light_vector(map, directions, options.rotate_degrees, options.threads);
  const std::string summary = "environment map " + map.name + " (" + layout_name(map.layout) +
                              ", " + std::to_string(map.radiance.width) + "x" +
                              std::to_string(map.radiance.height) + "), " +
                              std::to_string(directions.rows()) +
                              " lights: " + describe_coverage(vector) + negative_value_note(map);
  if (options.output.empty()) {
    // Rows on stdout (for pipes), the summary on stderr.
    note("%s", summary.c_str());
    for (Eigen::Index i = 0; i < vector.rgb.rows(); ++i)
      std::printf("%.9g %.9g %.9g\n", vector.rgb(i, 0), vector.rgb(i, 1), vector.rgb(i, 2));
    return;
  }
  write_rgb_rows(options.output, vector.rgb,
                 "light vector of " + map.name + " for " + options.directions + ", rotated " +
                     std::to_string(options.rotate_degrees) + " degrees about +y");
  say("%s\nwrote %s", summary.c_str(), options.output.c_str());
}

const CommandRegistration registration{
    25, [](CLI::App& app) {
      auto options = std::make_shared<LightsOptions>();
      auto* command = app.add_subcommand(
          "lights",
          "Sample an environment map onto light directions: each light gets the radiance x solid "
          "angle of its Voronoi cell on the sphere; directions farther from every light than the "
          "light set's median spacing count as outside and are reported, not used");
      command
          ->add_option("--dirs", options->directions,
                       "Light directions: a plain 'x y z' file, an RTI .lp file or a field folder "
                       "(camera frame: x right, y up, z towards the camera)")
          ->required();
      command
          ->add_option("--env", options->environment,
                       "Environment map, any format OpenImageIO reads (.hdr, .exr, ...)")
          ->required();
      command
          ->add_option("--layout", options->layout,
                       "Map layout: auto (2:1 latlong, 1:1 angular, 3:4 vertical cross), latlong, "
                       "angular or cross")
          ->capture_default_str();
      command
          ->add_option("--rotate", options->rotate_degrees,
                       "Rotate the environment about the up axis (+y) by this many degrees, "
                       "counter-clockwise seen from above (+90 brings light from +x to -z)")
          ->capture_default_str();
      command->add_option(
          "-o,--output", options->output,
          "Write the rows here (atomically) and the summary to stdout; default: rows "
          "to stdout, summary to stderr");
      command->add_option("--threads", options->threads, "Worker threads (default: all cores)");
      command->callback([options] { run_lights(*options); });
    }};

}  // namespace
}  // namespace relume
