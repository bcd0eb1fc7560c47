// The light source options shared by relighting commands: exactly one of `--lights FILE` (one
// `R G B` row per light) or `--env MAP` (with `--layout` and `--rotate`), resolved to a light
// vector for a given set of light directions.
#pragma once

#include <CLI/CLI.hpp>
#include <relume/field.hpp>
#include <string>

namespace relume {

struct LightSourceOptions {
  std::string lights_file;
  std::string environment;
  std::string layout = "auto";
  double rotate_degrees = 0;
};

void add_light_source_options(CLI::App& command, LightSourceOptions& options);

// The light vector for `directions`; prints the environment map's coverage to stderr.
LightRgb resolve_light_vector(const LightSourceOptions& options, const LightDirections& directions);

}  // namespace relume
