// Implementation of the viewer's frames (viewer.hpp); /info is viewer_info.cpp.
#include "commands/view/viewer.hpp"

#include <cstdio>

#include "commands/view/frame_views.hpp"
#include "container/container.hpp"
#include "core/elapsed_time.hpp"
#include "image/image_bytes.hpp"
#include "options/directional_light_options.hpp"
#include "options/image_output_options.hpp"
#include "options/light_source_options.hpp"
#include "options/number_or_auto.hpp"
#include "options/rotation_option.hpp"
#include "relight/relight_layout.hpp"

namespace relume {
namespace {

// The viewer holds the relit frame, the full-residual frame of the same light and the view made
// from them.
constexpr std::size_t frames_held = 3;

CompressedField read_viewed_container(const std::string& path) {
  CompressedField field = read_container(path);
  check_relight_memory(field, frames_held);
  return field;
}

// relume relight's defaults: exposure, light colour and spread, rotation; the residual cap of
// the view's own --residual (as relight's, "all" unless given); without maps a light from the
// camera's direction, with maps the first map.
FrameRequest relight_defaults(const ViewerSettings& settings, const CompressedField& field) {
  FrameRequest defaults;
  const DirectionalLightOptions moved_light;
  defaults.light.color = Eigen::Vector3d(moved_light.color.data());
  defaults.light.spread_degrees = moved_light.spread_degrees;
  defaults.light.rotate_degrees = parse_rotation_degrees(LightSourceOptions().rotate);
  defaults.light.map = 0;
  if (settings.maps.empty()) defaults.light.direction = DirectionalLight().direction;
  defaults.exposure = parse_finite_number(ImageOutputOptions().exposure, "--exposure", "stops");
  defaults.residual_cap = residual_cap(settings.renderer, field.lights);
  return defaults;
}

// A header value: `value` with `format` (printf).
std::string header_number(const char* format, double value) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

}  // namespace

Viewer::Viewer(const ViewerSettings& settings)
    : input_(settings.input),
      field_(read_viewed_container(settings.input)),
      lights_(field_.directions, settings.maps, settings.layout),
      renderer_(field_, settings.renderer.relighter),
      defaults_(relight_defaults(settings, field_)),
      stored_pixels_(stored_pixels_view(field_)) {}

EncodedFrame Viewer::frame(const std::multimap<std::string, std::string>& parameters) {
  const FrameRequest request =
      parse_frame_request(parameters, defaults_, {field_.lights, lights_.maps()});
  EncodedFrame encoded;
  encoded.content_type = format_content_type(request.format);
  ImageWriteOptions write;
  Image view;
  if (request.view == FrameView::mask) {
    view = stored_pixels_;
  } else {
    RelitFrame relit = renderer_.relight(lights_.light_vector(request.light), request.residual_cap);
    encoded.headers = {{"X-Relume-Render-Ms", header_number("%.3f", relit.render_ms)},
                       {"X-Relume-Kernel-Ms", header_number("%.3f", relit.kernel_ms)},
                       {"X-Relume-Residual-Cap", residual_cap_text(request.residual_cap)},
                       {"X-Relume-Residual-Error", header_number("%.6g", relit.residual_error)}};
    if (request.light.direction)
      encoded.headers.emplace_back("X-Relume-Light-Covered",
                                   lights_.covers(*request.light.direction) ? "1" : "0");
    if (request.view == FrameView::image) {
      view = std::move(relit.image);
      write.exposure = request.exposure;
    } else {
      const Image& reference = relit.reference ? *relit.reference : relit.image;
      view = request.format == FrameFormat::exr
                 ? absolute_difference(relit.image, reference)
                 : false_colour_error(relit.image, reference, field_.mask);
    }
  }
  const auto start = Clock::now();
  encoded.bytes = encode_image_bytes(format_extension(request.format), view, write);
  encoded.headers.emplace_back("X-Relume-Encode-Ms",
                               header_number("%.3f", 1e3 * seconds_since(start)));
  return encoded;
}

}  // namespace relume
