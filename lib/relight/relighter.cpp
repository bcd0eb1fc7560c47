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
  bool project_non_negative = false;  // the field is non-negative and negatives are not allowed
  std::uint64_t projected = 0;        // values set to 0 by the last call

  // Sets `image`'s negative values to 0 when the field and `light` are non-negative; NaN stays.
  void project(const LightRgb& light, Image& image) {
    if (!project_non_negative || (light.array() < 0).any()) return;
    for (float& value : image.pixels)
      if (value < 0) {
        value = 0;
        ++projected;
      }
  }
};

Relighter::Relighter(const CompressedField& field, const RelighterOptions& options)
    : backend_(std::make_unique<Backend>()) {
  if (!options.cpu_reference) {
    backend_->context = std::make_unique<OpenClContext>(select_opencl_device(options.device));
    backend_->relighter = std::make_unique<OpenClRelighter>(*backend_->context, field);
  } else {
    backend_->reference = std::make_unique<CompressedRelightReference>(field);  // checks it once
  }
  backend_->project_non_negative = field.non_negative && !options.allow_negative;
}

Relighter::~Relighter() = default;

Image Relighter::relight(const LightRgb& light, int residual_cap) {
  backend_->projected = 0;
  Image image = backend_->relighter ? backend_->relighter->relight(light, residual_cap)
                                    : backend_->reference->relight(light, residual_cap);
  backend_->project(light, image);
  return image;
}

std::vector<Image> Relighter::relight_batch(const std::vector<LightRgb>& lights, int residual_cap) {
  backend_->projected = 0;
  std::vector<Image> images;
  if (backend_->relighter) {
    images = backend_->relighter->relight_batch(lights, residual_cap);
  } else {
    for (const auto& light : lights)
      images.push_back(backend_->reference->relight(light, residual_cap));
  }
  for (std::size_t b = 0; b < images.size(); ++b) backend_->project(lights[b], images[b]);
  return images;
}

std::uint64_t Relighter::last_projected_values() const { return backend_->projected; }

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
