// The relighting options `relight` and `relight-sequence` share: the device (or the CPU
// reference) for relume::Relighter, and the residual cap as users write it.
#pragma once

#include <CLI/CLI.hpp>
#include <relume/relight.hpp>
#include <string>

namespace relume {

struct RendererOptions {
  RelighterOptions relighter;
  std::string residual = "all";  // "all", N entries, or P% of the lights
};

void add_renderer_options(CLI::App& command, RendererOptions& options);

// Throws Error naming a malformed --residual value; commands call it before loading anything.
void check_renderer_options(const RendererOptions& options);

// The residual cap of `options.residual` for a field of `lights` lights (full_residual for "all").
// Throws Error naming a malformed value.
int residual_cap(const RendererOptions& options, int lights);

}  // namespace relume
