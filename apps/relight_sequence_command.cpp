// `relume relight-sequence`: an animated relighting of a .relume container, either one map rotated
// by a fixed step per frame or one map per frame from a list. Frames are relit B at a time in one
// pass over W and the residual, written as numbered images, and the run reports frames/s, the
// kernels' GB/s and, with --compare, each frame's error against the full-residual render.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/lighting.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/progress.hpp"
#include "image/image_difference.hpp"
#include "json_report.hpp"
#include "lighting/environment_map.hpp"
#include "relight/compressed_relight_reference.hpp"
#include "renderer_options.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

struct SequenceOptions {
  std::string input;
  std::string environment;
  std::string environment_list;
  std::string layout = "auto";
  int frames = 36;
  double rotate_start = 0;
  double rotate_step = 10;
  std::string output_pattern;
  int batch = 16;
  double exposure = 0;
  bool compare = false;
  std::string report;
  RendererOptions renderer;
};

// The frame's file name from a printf pattern with one integer conversion (frames/%04d.png).
std::string frame_path(const std::string& pattern, int frame) {
  std::vector<char> buffer(pattern.size() + 32);
  std::snprintf(buffer.data(), buffer.size(), pattern.c_str(), frame);
  return buffer.data();
}

void check_pattern(const std::string& pattern) {
  const auto percent = pattern.find('%');
  const bool one_conversion = percent != std::string::npos &&
                              pattern.find('%', percent + 1) == std::string::npos &&
                              pattern.find_first_of("d", percent) != std::string::npos;
  if (!one_conversion)
    throw Error("output pattern '" + pattern +
                "' needs exactly one frame-number conversion such as %04d (frames/%04d.png)");
  const std::size_t d = pattern.find('d', percent);
  for (std::size_t i = percent + 1; i < d; ++i)
    if (!std::isdigit(static_cast<unsigned char>(pattern[i])))
      throw Error("output pattern '" + pattern + "': only %d with a width (%04d) is supported");
}

std::vector<std::string> read_map_list(const std::string& list) {
  std::ifstream in(list);
  if (!in) throw Error("cannot open environment list " + list);
  std::vector<std::string> maps;
  const fs::path folder = fs::path(list).parent_path();
  for (std::string line; std::getline(in, line);) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty() || line[0] == '#') continue;
    maps.push_back(fs::path(line).is_absolute() ? line : (folder / line).string());
  }
  if (maps.empty()) throw Error("environment list " + list + " names no maps");
  return maps;
}

// The light vector of every frame.
std::vector<LightRgb> frame_lights(const SequenceOptions& options, const CompressedField& field) {
  const auto layout = parse_layout_option(options.layout);
  std::vector<LightRgb> lights;
  if (!options.environment_list.empty()) {
    for (const auto& map_path : read_map_list(options.environment_list))
      lights.push_back(integrate_light_vector(load_environment_map(map_path, layout),
                                              field.directions, options.rotate_start)
                           .rgb);
    return lights;
  }
  if (options.frames < 1) throw Error("--frames must be at least 1");
  const LightVectorIntegrator integrator(load_environment_map(options.environment, layout),
                                         field.directions);
  for (int frame = 0; frame < options.frames; ++frame)
    lights.push_back(integrator.integrate(options.rotate_start + frame * options.rotate_step).rgb);
  note("%s: %s", options.environment.c_str(),
       describe_coverage(integrator.integrate(options.rotate_start)).c_str());
  return lights;
}

void run_sequence(const SequenceOptions& options) {
  check_pattern(options.output_pattern);
  if (options.batch < 1) throw Error("--batch must be at least 1");
  check_renderer_options(options.renderer);
  const fs::path folder = fs::path(frame_path(options.output_pattern, 0)).parent_path();
  if (!folder.empty()) check_output_folder_location(folder);
  if (!options.report.empty()) check_output_file_location(options.report);
  const CompressedField field = read_container(options.input);
  const std::vector<LightRgb> lights = frame_lights(options, field);
  check_relight_memory(field, std::min<std::size_t>(std::size_t(options.batch), lights.size()) *
                                  (options.compare ? 2 : 1));
  Relighter renderer(field, options.renderer.relighter);
  const int cap = residual_cap(options.renderer, field.lights);
  if (!folder.empty()) fs::create_directories(folder);

  using clock = std::chrono::steady_clock;
  double relight_seconds = 0, kernel_seconds = 0, kernel_bytes = 0;
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  ProgressReporter progress("relight-sequence", lights.size());
  for (std::size_t first = 0; first < lights.size(); first += options.batch) {
    const std::size_t count = std::min<std::size_t>(options.batch, lights.size() - first);
    const std::vector<LightRgb> batch(lights.begin() + first, lights.begin() + first + count);
    const auto start = clock::now();
    const std::vector<Image> images = renderer.relight_batch(batch, cap);
    relight_seconds += std::chrono::duration<double>(clock::now() - start).count();
    kernel_seconds += renderer.last_kernel_seconds();
    kernel_bytes += renderer.last_kernel_bytes();
    std::vector<Image> references;
    if (options.compare) references = renderer.relight_batch(batch, full_residual);
    for (std::size_t b = 0; b < count; ++b) {
      const int frame = static_cast<int>(first + b);
      write_image(frame_path(options.output_pattern, frame), images[b], {options.exposure});
      nlohmann::ordered_json record = {{"frame", frame},
                                       {"file", frame_path(options.output_pattern, frame)}};
      if (options.compare)
        record["error"] = image_difference(images[b], references[b]).relative_squared_error;
      frames.push_back(record);
      progress.advance();
    }
  }
  progress.finish();

  const double fps = relight_seconds > 0 ? lights.size() / relight_seconds : 0;
  const double gbps = kernel_seconds > 0 ? 1e-9 * kernel_bytes / kernel_seconds : 0;
  say("%zu frames on %s, batch %d, residual cap %s: %.1f frames/s relighting (%.2f s), "
      "kernels %.2f GB/s",
      lights.size(), renderer.device_name().c_str(), options.batch,
      cap == full_residual ? "all" : std::to_string(cap).c_str(), fps, relight_seconds, gbps);
  if (options.compare) {
    double worst = 0;
    for (const auto& f : frames) worst = std::max(worst, f["error"].get<double>());
    say("largest per-frame relative squared error against the full residual: %.3g", worst);
  }
  if (!options.report.empty()) {
    const nlohmann::ordered_json report = {{"device", renderer.device_name()},
                                           {"frames", lights.size()},
                                           {"batch", options.batch},
                                           {"residual_cap", cap == full_residual ? -1 : cap},
                                           {"relight_seconds", relight_seconds},
                                           {"frames_per_second", fps},
                                           {"kernel_gbps", gbps},
                                           {"per_frame", frames}};
    write_json_report(options.report, report);
  }
}

const CommandRegistration registration{
    35, [](CLI::App& app) {
      auto options = std::make_shared<SequenceOptions>();
      auto* command = app.add_subcommand("relight-sequence",
                                         "Relight a .relume container under a rotating environment "
                                         "or a list of maps, one image per "
                                         "frame");
      command->add_option("input", options->input, "The .relume container")->required();
      auto* env =
          command->add_option("--env", options->environment,
                              "Environment map rotated about +y by --rotate-step per frame");
      auto* list = command->add_option("--env-list", options->environment_list,
                                       "Text file naming one environment map per frame (paths "
                                       "relative to the list's folder)");
      env->excludes(list);
      list->excludes(env);
      command->add_option("--layout", options->layout, "Map layout: auto, latlong, angular, cross")
          ->capture_default_str();
      command->add_option("--frames", options->frames, "Frames to render with --env")
          ->capture_default_str();
      command->add_option("--rotate", options->rotate_start, "Rotation of the first frame, degrees")
          ->capture_default_str();
      command
          ->add_option("--rotate-step", options->rotate_step, "Rotation added per frame, degrees")
          ->capture_default_str();
      command
          ->add_option("-o,--output", options->output_pattern,
                       "Frame file pattern with one %d conversion, e.g. frames/%04d.exr or .png")
          ->required();
      command
          ->add_option("--batch", options->batch,
                       "Frames relit together in one pass over the compressed data")
          ->capture_default_str();
      command->add_option("--exposure", options->exposure, "Exposure in stops for 8-bit outputs")
          ->capture_default_str();
      command->add_flag("--compare", options->compare,
                        "Also render each frame with the full residual and report the error");
      command->add_option("--report", options->report, "Write a JSON report of the run");
      add_renderer_options(*command, options->renderer);
      command->callback([options] {
        if (options->environment.empty() && options->environment_list.empty())
          throw Error("give --env MAP (rotating) or --env-list FILE");
        run_sequence(*options);
      });
    }};

}  // namespace
}  // namespace relume
