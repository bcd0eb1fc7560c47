// The options of `relume relight-sequence` and the light vector of each of its frames: an
// environment map turned step by step, a list of maps, or a directional light moved along an orbit
// or a path of directions (between the captured lights, as `relume relight --light-dir` moves it).
#pragma once

#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/lighting.hpp>
#include <string>
#include <vector>

#include "options/directional_light_options.hpp"
#include "options/image_output_options.hpp"
#include "options/renderer_options.hpp"

namespace relume {

struct SequenceOptions {
  std::string input;
  std::string environment;
  std::string environment_list;
  std::string layout = "auto";
  std::optional<double> orbit_elevation;
  std::string light_path;
  DirectionalLightOptions moved_light;
  int frames = 36;
  std::string rotate_start = "0";  // degrees or "auto"
  double rotate_step = 10;
  std::string output_pattern;
  int batch = 16;
  int start_number = 0;
  std::string video;
  int video_fps = 24;
  std::string video_codec;
  ImageOutputOptions image_output;
  bool compare = false;
  std::string report;
  RendererOptions renderer;
};

// The light vector of every frame, as `options` asks, for the lights of `field`.
std::vector<LightRgb> frame_lights(const SequenceOptions& options, const CompressedField& field);

}  // namespace relume
