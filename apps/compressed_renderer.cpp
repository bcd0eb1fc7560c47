// Implementation of the command-side renderer over the OpenCL and reference relighters.
#include "compressed_renderer.hpp"

#include "relight/compressed_relight_reference.hpp"
#include "relight/opencl_relighter.hpp"
#include "compress/residual_selection.hpp"

namespace relume {

// Exactly one of `relighter` (with its context) and `reference` is set.
struct CompressedRenderer::Backend {
  std::unique_ptr<OpenClContext> context;
  std::unique_ptr<OpenClRelighter> relighter;
  std::unique_ptr<CompressedRelightReference> reference;
};

void add_renderer_options(CLI::App& command, RendererOptions& options) {
  command.add_option("--device", options.device,
                     "OpenCL device: a substring of 'platform / device' (see `relume devices`); "
                     "default RELUME_DEVICE, else a GPU, else PoCL's CPU device");
  command.add_flag("--cpu", options.cpu_reference,
                   "Relight with the plain C++ reference instead of OpenCL");
  command.add_option("--residual", options.residual,
                     "Residual entries used per function: 'all', a count N, or P% of the lights "
                     "(fewer is faster and less accurate)")
      ->capture_default_str();
}

CompressedRenderer::CompressedRenderer(const CompressedField& field, const RendererOptions& options)
    : backend_(std::make_unique<Backend>()),
      residual_cap_(options.residual == "all"
                        ? full_residual
                        : parse_residual_budget(options.residual).entries_for(field.lights)) {
  if (!options.cpu_reference) {
    backend_->context = std::make_unique<OpenClContext>(select_opencl_device(options.device));
    backend_->relighter = std::make_unique<OpenClRelighter>(*backend_->context, field);
  } else {
    backend_->reference = std::make_unique<CompressedRelightReference>(field);  // checks it once
  }
}

CompressedRenderer::~CompressedRenderer() = default;

std::vector<Image> CompressedRenderer::render(const std::vector<LightRgb>& lights) {
  return render(lights, residual_cap_);
}

std::vector<Image> CompressedRenderer::render(const std::vector<LightRgb>& lights, int cap) {
  if (backend_->relighter) return backend_->relighter->relight_batch(lights, cap);
  std::vector<Image> images;
  for (const auto& light : lights)
    images.push_back(backend_->reference->relight(light, cap));
  return images;
}

std::string CompressedRenderer::device_name() const {
  return backend_->context ? backend_->context->device().label() : "CPU reference (C++)";
}

double CompressedRenderer::last_kernel_bytes() const {
  return backend_->relighter ? double(backend_->relighter->last_timing().kernel_bytes()) : 0;
}

double CompressedRenderer::last_kernel_seconds() const {
  return backend_->relighter ? backend_->relighter->last_timing().kernel_seconds() : 0;
}

}  // namespace relume
