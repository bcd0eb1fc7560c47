// Implementation of the eval's relighting measurements (see relighting_measures.hpp).
#include "eval/relighting_measures.hpp"

#include <algorithm>
#include <relume/error.hpp>
#include <relume/relight.hpp>

#include "core/elapsed_time.hpp"
#include "core/progress.hpp"
#include "image/image_difference.hpp"

namespace relume {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t half = values.size() / 2;
  return values.size() % 2 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

}  // namespace

RelightingResult measure_relighting(
    const std::vector<std::pair<std::string, const CompressedField*>>& fields,
    const RelightingSetup& setup) {
  if (setup.frames < 1 || setup.timed_calls < 1)
    throw Error("relighting needs at least one frame and one timed call, got " +
                std::to_string(setup.frames) + " and " + std::to_string(setup.timed_calls));
  const ReflectanceField& original = *setup.original;
  const LightVectorIntegrator integrator(*setup.map, original.directions, setup.threads);
  std::vector<LightRgb> lights;
  std::vector<Image> references;
  for (int frame = 0; frame < setup.frames; ++frame) {
    lights.push_back(integrator.integrate(setup.rotate_degrees + 360.0 * frame / setup.frames).rgb);
    references.push_back(relight_field(original, lights.back(), setup.threads));
  }
  RelightingResult result;
  result.reference = references.front();
  ProgressReporter progress("eval: relighting", fields.size() * setup.caps.size(), true);
  for (const auto& [method, field] : fields) {
    RelighterOptions options;
    options.device = setup.device;
    options.allow_negative = true;  // each method's own reconstruction, not projected onto >= 0
    Relighter relighter(*field, options);
    result.device = relighter.device_name();
    relighter.relight(lights.front());  // warm-up: buffers and kernels
    for (const int cap : setup.caps) {
      double error = 0;
      for (int frame = 0; frame < setup.frames; ++frame) {
        const Image image = relighter.relight(lights[frame], cap);
        error +=
            image_difference(image, references[frame], method, "reference").relative_squared_error;
        if (frame == 0 && cap == setup.image_cap) result.images.emplace_back(method, image);
      }
      std::vector<double> seconds, kernel_seconds;
      for (int call = 0; call < setup.timed_calls; ++call) {
        const auto start = Clock::now();
        relighter.relight(lights[call % setup.frames], cap);
        seconds.push_back(seconds_since(start));
        kernel_seconds.push_back(relighter.last_kernel_seconds());
      }
      RelightingRow row;
      row.method = method;
      row.cap = cap;
      const double frame_seconds = median(seconds);
      row.frames_per_second = frame_seconds > 0 ? 1.0 / frame_seconds : 0;
      row.kernel_ms = 1e3 * median(kernel_seconds);
      row.relit_error = error / setup.frames;
      row.error_masked = relative_error(original, *field, true, cap, setup.threads).mean;
      if (setup.on_row) setup.on_row(row);
      result.rows.push_back(row);
      progress.advance();
    }
  }
  progress.finish();
  return result;
}

}  // namespace relume
