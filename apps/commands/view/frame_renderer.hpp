// The render worker of `relume view`: the one relume::Relighter of the field (uploaded once),
// used by one request at a time (the HTTP server answers requests on several threads; a mutex
// serialises them), and the error of a residual cap measured against the full-residual frame of
// the same light, which is kept so that moving the cap or switching views under a fixed light
// renders only the capped frame.
#pragma once

#include <mutex>
#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/image.hpp>
#include <relume/relight.hpp>
#include <string>

namespace relume {

struct RelitFrame {
  Image image;                     // relit with the cap
  std::optional<Image> reference;  // the full-residual frame, when the cap leaves entries out
  double render_ms = 0;            // wall clock of the capped relight (kernels and read-back)
  double kernel_ms = 0;            // the device time of its kernels
  // Relative squared error of `image` against the full-residual frame (sum (a - r)^2 / sum r^2,
  // image/image_difference.hpp); 0 when the cap keeps every entry.
  double residual_error = 0;
};

class FrameRenderer {
 public:
  // Throws Error as Relighter does (an inconsistent field, no OpenCL device that matches).
  FrameRenderer(const CompressedField& field, const RelighterOptions& options);

  // Thread-safe. residual_cap >= 0 (all_residual_entries: every entry).
  RelitFrame relight(const LightRgb& light, int residual_cap);

  std::string device_name() const { return device_name_; }
  // The longest residual row: a cap at or above it keeps every entry.
  int longest_residual_row() const { return longest_row_; }

 private:
  std::mutex mutex_;
  Relighter relighter_;
  std::string device_name_;
  int longest_row_ = 0;
  LightRgb reference_light_;  // the light of reference_ (empty: none yet)
  Image reference_;
};

}  // namespace relume
