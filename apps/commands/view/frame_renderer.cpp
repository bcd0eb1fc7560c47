// Implementation of the viewer's render worker (frame_renderer.hpp).
#include "commands/view/frame_renderer.hpp"

#include "core/elapsed_time.hpp"
#include "image/image_difference.hpp"

namespace relume {

FrameRenderer::FrameRenderer(const CompressedField& field, const RelighterOptions& options)
    : relighter_(field, options),
      device_name_(relighter_.device_name()),
      longest_row_(int(field.residual.longest_row())) {}

RelitFrame FrameRenderer::relight(const LightRgb& light, int residual_cap) {
  const std::lock_guard<std::mutex> lock(mutex_);
  RelitFrame frame;
  const auto start = Clock::now();
  frame.image = relighter_.relight(light, residual_cap);
  frame.render_ms = 1e3 * seconds_since(start);
  frame.kernel_ms = 1e3 * relighter_.last_kernel_seconds();
  if (residual_cap >= longest_row_) return frame;
  if (reference_light_.rows() != light.rows() || reference_light_ != light) {
    reference_ = relighter_.relight(light, all_residual_entries);
    reference_light_ = light;
  }
  frame.reference = reference_;
  frame.residual_error =
      image_difference(frame.image, reference_, "the capped frame", "the full-residual frame")
          .relative_squared_error;
  return frame;
}

}  // namespace relume
