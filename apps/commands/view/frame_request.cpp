// Implementation of the /frame query parameters (frame_request.hpp).
#include "commands/view/frame_request.hpp"

#include <algorithm>
#include <iterator>
#include <vector>

#include "core/text_numbers.hpp"
#include "lighting/light_interpolation.hpp"
#include "options/renderer_options.hpp"

namespace relume {
namespace {

using Parameters = std::multimap<std::string, std::string>;

// In the order of the enumerations.
struct FormatNames {
  const char* name;
  const char* extension;  // for write_image / encode_image_bytes
  const char* content_type;
};
constexpr FormatNames formats[] = {
    {"png", ".png", "image/png"}, {"jpeg", ".jpg", "image/jpeg"}, {"exr", ".exr", "image/x-exr"}};
constexpr const char* view_names[] = {"image", "error", "mask"};

const char* const known_parameters[] = {"light",    "rotate",   "map",    "color", "spread",
                                        "exposure", "residual", "format", "view"};

BadRequest bad_value(const std::string& name, const std::string& value, const std::string& why) {
  return BadRequest(name + "=" + value + ": " + why);
}

void check_names(const Parameters& parameters) {
  for (auto it = parameters.begin(); it != parameters.end();
       it = parameters.upper_bound(it->first)) {
    bool known = false;
    for (const char* name : known_parameters) known = known || it->first == name;
    if (!known) {
      std::string list;
      for (const char* name : known_parameters)
        list += std::string(list.empty() ? "" : ", ") + name;
      throw BadRequest("unknown parameter '" + it->first + "' (known: " + list + ")");
    }
    if (parameters.count(it->first) > 1)
      throw BadRequest("parameter '" + it->first + "' is given more than once");
  }
}

const std::string* find(const Parameters& parameters, const std::string& name) {
  const auto it = parameters.find(name);
  return it == parameters.end() ? nullptr : &it->second;
}

double number(const std::string& name, const std::string& text) {
  const std::optional<double> value = parse_finite_double(text);
  if (!value) throw bad_value(name, text, "expected a finite number");
  return *value;
}

double number_in(const std::string& name, const std::string& text, double low, double high) {
  const double value = number(name, text);
  if (value < low || value > high)
    throw bad_value(name, text, "expected a number from " + number_text(low) + " to " + number_text(high));
  return value;
}

// "x,y,z": three finite numbers.
Eigen::Vector3d triple(const std::string& name, const std::string& text) {
  std::vector<std::string> parts(1);
  for (const char c : text) {
    if (c == ',')
      parts.emplace_back();
    else
      parts.back() += c;
  }
  if (parts.size() != 3) throw bad_value(name, text, "expected three numbers x,y,z");
  Eigen::Vector3d value;
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> part = parse_finite_double(parts[i]);
    if (!part) throw bad_value(name, text, "'" + parts[i] + "' is not a finite number");
    value[i] = *part;
  }
  return value;
}

FrameLight parse_light(const Parameters& parameters, const FrameLight& defaults,
                       const FrameLimits& limits) {
  FrameLight light = defaults;
  const std::string* direction = find(parameters, "light");
  const std::string* rotate = find(parameters, "rotate");
  const std::string* map = find(parameters, "map");
  if (direction && (rotate || map))
    throw BadRequest("give light=x,y,z or rotate=DEG&map=I, not both");
  if (direction) {
    light.direction = triple("light", *direction);
    if (light.direction->norm() == 0) throw bad_value("light", *direction, "the direction is zero");
  }
  if (rotate || map) {
    const std::string& given = rotate ? *rotate : *map;
    if (limits.maps == 0)
      throw bad_value(rotate ? "rotate" : "map", given,
                      "relume view was started without --env maps");
    light.direction.reset();
    if (rotate) light.rotate_degrees = number("rotate", *rotate);
    if (map) {
      const std::optional<std::uint64_t> index = parse_unsigned(*map);
      if (!index || *index >= std::uint64_t(limits.maps))
        throw bad_value("map", *map,
                        "expected a map index from 0 to " + std::to_string(limits.maps - 1));
      light.map = int(*index);
    }
  }
  if (const std::string* color = find(parameters, "color")) {
    light.color = triple("color", *color);
    if (light.color.minCoeff() < 0 || light.color.maxCoeff() > max_light_color)
      throw bad_value("color", *color, "expected components from 0 to " + number_text(max_light_color));
  }
  if (const std::string* spread = find(parameters, "spread")) {
    if (!light.direction)
      throw bad_value("spread", *spread, "a spread applies to a directional light (light=x,y,z)");
    light.spread_degrees = number_in("spread", *spread, 0, 90);
  }
  return light;
}

}  // namespace

const char* format_name(FrameFormat format) { return formats[int(format)].name; }
const char* format_extension(FrameFormat format) { return formats[int(format)].extension; }
const char* format_content_type(FrameFormat format) { return formats[int(format)].content_type; }
const char* view_name(FrameView view) { return view_names[int(view)]; }

FrameRequest parse_frame_request(const Parameters& parameters, const FrameRequest& defaults,
                                 const FrameLimits& limits) {
  check_names(parameters);
  FrameRequest request = defaults;
  request.light = parse_light(parameters, defaults.light, limits);
  if (const std::string* exposure = find(parameters, "exposure"))
    request.exposure = number_in("exposure", *exposure, -max_exposure_stops, max_exposure_stops);
  if (const std::string* residual = find(parameters, "residual")) {
    RendererOptions renderer;
    renderer.residual = *residual;
    try {
      request.residual_cap = residual_cap(renderer, limits.lights);
    } catch (const Error& e) {
      throw bad_value("residual", *residual, e.what());
    }
  }
  if (const std::string* format = find(parameters, "format")) {
    const auto* known = std::find_if(std::begin(formats), std::end(formats),
                                     [&](const FormatNames& f) { return *format == f.name; });
    if (known == std::end(formats)) throw bad_value("format", *format, "expected png, jpeg or exr");
    request.format = FrameFormat(known - std::begin(formats));
  }
  if (const std::string* view = find(parameters, "view")) {
    const auto* known = std::find(std::begin(view_names), std::end(view_names), *view);
    if (known == std::end(view_names))
      throw bad_value("view", *view, "expected image, error or mask");
    request.view = FrameView(known - std::begin(view_names));
  }
  return request;
}

}  // namespace relume
