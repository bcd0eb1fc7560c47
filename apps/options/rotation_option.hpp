// `--rotate DEG|auto` for the commands that light with an environment map (relight, lights,
// relight-sequence): a number of degrees about the up axis, or auto, the rotation that puts the
// most of the map's energy on the light set (lighting/best_rotation.hpp). Resolving it also
// gives the information line about the energy outside the light set, naming the best rotation
// where another one would leave clearly less outside.
#pragma once

#include <CLI/CLI.hpp>
#include <relume/lighting.hpp>
#include <string>

namespace relume {

// Adds --rotate with `help` (the text says what auto does).
CLI::Option* add_rotation_option(CLI::App& command, std::string& rotate, const std::string& help);

// A --rotate value that must be a number. Throws Error naming the value otherwise.
double parse_rotation_degrees(const std::string& text);

struct ResolvedRotation {
  double degrees = 0;
  std::string information;  // the coverage line for users (a note)
};

// `rotate` is a finite number of degrees or "auto". The best rotation is searched for auto, and
// otherwise only when more than 1% of the map's energy falls outside at the given rotation.
// Throws Error naming the value when it is neither.
ResolvedRotation resolve_rotation(const std::string& rotate,
                                  const LightVectorIntegrator& integrator);

}  // namespace relume
