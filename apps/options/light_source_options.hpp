// The light source options shared by relighting commands: exactly one of `--lights FILE` (one
// `R G B` row per light), `--env MAP` (with `--layout` and `--rotate`) or `--light-dir x,y,z` (a
// moved light, with `--light-color` and `--spread`), resolved to a light vector for a given set
// of light directions.
#pragma once

#include <CLI/CLI.hpp>
#include <relume/field.hpp>
#include <string>

#include "options/directional_light_options.hpp"

namespace relume {

struct LightSourceOptions {
  std::string lights_file;
  std::string environment;
  std::string layout = "auto";
  std::string rotate = "0";  // degrees or "auto"
  DirectionalLightOptions moved_light;
};

void add_light_source_options(CLI::App& command, LightSourceOptions& options);

// The light vector for `directions`; notes the environment map's coverage.
LightRgb resolve_light_vector(const LightSourceOptions& options, const LightDirections& directions);

}  // namespace relume
