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

// Checks what can be checked before loading anything: a malformed --residual value, and that
// --device names an OpenCL device (unless --cpu). Throws Error (listing the devices when nothing
// matches).
void check_renderer_options(const RendererOptions& options);

// The residual cap of `options.residual` for a field of `lights` lights (all_residual_entries for
// "all"). Throws Error naming a malformed value.
int residual_cap(const RendererOptions& options, int lights);

// A cap as users write it: "all" for all_residual_entries, else the count.
std::string residual_cap_text(int residual_cap);

}  // namespace relume
