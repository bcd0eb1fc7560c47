// Implementation of the shared relighting options.
#include "options/renderer_options.hpp"

#include "compress/residual_selection.hpp"
#include "opencl/runtime.hpp"

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
  command.add_flag("--allow-negative", options.relighter.allow_negative,
                   "Keep negative relit values: by default a container of non-negative data relit "
                   "under a non-negative light has its undershoot below zero set to 0 (the true "
                   "image is >= 0 there); use this to see the raw reconstruction");
}

void check_renderer_options(const RendererOptions& options) {
  if (options.residual != "all") ResidualBudget::parse(options.residual);
  if (!options.relighter.cpu_reference) select_opencl_device(options.relighter.device);
}

int residual_cap(const RendererOptions& options, int lights) {
  if (options.residual == "all") return all_residual_entries;
  return ResidualBudget::parse(options.residual).entries_for(lights);
}

std::string residual_cap_text(int residual_cap) {
  return residual_cap == all_residual_entries ? "all" : std::to_string(residual_cap);
}

}  // namespace relume
