// Implementation of the shared relighting options.
#include "renderer_options.hpp"

#include "compress/residual_selection.hpp"

namespace relume {

void add_renderer_options(CLI::App& command, RendererOptions& options) {
  command.add_option("--device", options.relighter.device,
                     "OpenCL device: a substring of 'platform / device' (see `relume devices`); "
                     "default RELUME_DEVICE, else a GPU, else PoCL's CPU device");
  command.add_flag("--cpu", options.relighter.cpu_reference,
                   "Relight with the plain C++ reference instead of OpenCL");
  command
      .add_option("--residual", options.residual,
                  "Residual entries used per function: 'all', a count N, or P% of the lights "
                  "(fewer is faster and less accurate)")
      ->capture_default_str();
}

void check_renderer_options(const RendererOptions& options) {
  if (options.residual != "all") parse_residual_budget(options.residual);
}

int residual_cap(const RendererOptions& options, int lights) {
  if (options.residual == "all") return full_residual;
  return parse_residual_budget(options.residual).entries_for(lights);
}

}  // namespace relume
