// Implementation of the public Relighter (relume/relight.hpp) over the OpenCL relighter and the
// CPU reference.
#include <relume/relight.hpp>

#include "relight/compressed_relight_reference.hpp"
#include "relight/opencl_relighter.hpp"

namespace relume {

// Exactly one of `relighter` (with its context) and `reference` is set.
struct Relighter::Backend {
  std::unique_ptr<OpenClContext> context;
  std::unique_ptr<OpenClRelighter> relighter;
  std::unique_ptr<CompressedRelightReference> reference;
};

Relighter::Relighter(const CompressedField& field, const RelighterOptions& options)
    : backend_(std::make_unique<Backend>()) {
  if (!options.cpu_reference) {
    backend_->context = std::make_unique<OpenClContext>(select_opencl_device(options.device));
    backend_->relighter = std::make_unique<OpenClRelighter>(*backend_->context, field);
  } else {
    backend_->reference = std::make_unique<CompressedRelightReference>(field);  // checks it once
  }
}

Relighter::~Relighter() = default;

Image Relighter::relight(const LightRgb& light, int residual_cap) {
  if (backend_->relighter) return backend_->relighter->relight(light, residual_cap);
  return backend_->reference->relight(light, residual_cap);
}

std::vector<Image> Relighter::relight_batch(const std::vector<LightRgb>& lights, int residual_cap) {
  if (backend_->relighter) return backend_->relighter->relight_batch(lights, residual_cap);
  std::vector<Image> images;
  for (const auto& light : lights)
    images.push_back(backend_->reference->relight(light, residual_cap));
  return images;
}

std::string Relighter::device_name() const {
  return backend_->context ? backend_->context->device().label() : "CPU reference (C++)";
}

double Relighter::last_kernel_bytes() const {
  return backend_->relighter ? double(backend_->relighter->last_timing().kernel_bytes()) : 0;
}

double Relighter::last_kernel_seconds() const {
  return backend_->relighter ? backend_->relighter->last_timing().kernel_seconds() : 0;
}

}  // namespace relume
