// The relighting side of `relume eval` (paper Table 1): frames per second and the relit error per
// residual cap of the OpenCL relighter, on the fields as their containers store them, under an
// environment map turned through a few rotations; and the relit images of one cap.
#pragma once

#include <functional>
#include <relume/compressed_field.hpp>
#include <relume/image.hpp>
#include <relume/lighting.hpp>
#include <string>
#include <vector>

namespace relume {

struct RelightingRow {
  std::string method;
  int cap = 0;
  double frames_per_second = 0;  // 1 / median wall time of one relight() call (with readback)
  double kernel_ms = 0;          // median device time of its kernels
  double relit_error = 0;   // relative squared error against the uncompressed field relit, mean
                            // over the frames
  double error_masked = 0;  // Eq. 16 error of the stored field with this cap, inside the mask
};

struct RelightingSetup {
  const ReflectanceField* original = nullptr;
  const EnvironmentMap* map = nullptr;
  double rotate_degrees = 0;  // of the first frame; the others turn on by 360 / frames
  int frames = 8;
  int timed_calls = 24;   // relight() calls timed per cap, cycling through the frames
  std::vector<int> caps;  // residual entries used per row
  int image_cap = 0;      // the cap whose first frame is kept as the relit image
  std::string device;     // OpenCL device (RelighterOptions::device)
  unsigned threads = 0;
  std::function<void(const RelightingRow& row)> on_row;  // told each row as it is measured
};

struct RelightingResult {
  std::string device;
  std::vector<RelightingRow> rows;
  Image reference;                                    // the first frame, uncompressed
  std::vector<std::pair<std::string, Image>> images;  // per method, image_cap, first frame
};

// `fields`: (method name, stored field) pairs. Reports progress per method and cap to the
// thread's listener only (lib/core/progress.hpp); interruptible. Throws Error when no OpenCL
// device matches.
RelightingResult measure_relighting(
    const std::vector<std::pair<std::string, const CompressedField*>>& fields,
    const RelightingSetup& setup);

}  // namespace relume
