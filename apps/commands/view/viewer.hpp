// What `relume view` serves, apart from HTTP: the field read from its container, the lights of its
// frames, the render worker, and the answers to `GET /info` (viewer_info.cpp) and `GET /frame`
// (a request's parameters to an encoded image with its timing headers).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <relume/compressed_field.hpp>
#include <string>
#include <utility>
#include <vector>

#include "options/renderer_options.hpp"
#include "commands/view/frame_renderer.hpp"
#include "commands/view/frame_request.hpp"
#include "commands/view/view_lights.hpp"

namespace relume {

struct ViewerSettings {
  std::string input;              // the .relume container
  std::vector<std::string> maps;  // --env
  std::string layout = "auto";    // --layout of the maps
  RendererOptions renderer;       // --device / --cpu, and --residual, the default cap
};

struct EncodedFrame {
  std::string bytes;
  const char* content_type = "";
  std::vector<std::pair<std::string, std::string>> headers;  // X-Relume-* (docs/viewer.md)
};

class Viewer {
 public:
  // Reads the container and the maps and uploads the field. Throws Error.
  explicit Viewer(const ViewerSettings& settings);

  // The frame `parameters` ask for (frame_request.hpp). Throws BadRequest for a bad request and
  // Error when rendering or encoding fails. Thread-safe.
  EncodedFrame frame(const std::multimap<std::string, std::string>& parameters);

  // The /info document (viewer_info.cpp).
  nlohmann::ordered_json info() const;

 private:
  std::string input_;
  CompressedField field_;
  ViewLights lights_;
  FrameRenderer renderer_;
  FrameRequest defaults_;
  Image stored_pixels_;  // the mask view, made once
};

}  // namespace relume
