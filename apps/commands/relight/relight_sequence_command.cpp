// `relume relight-sequence`: an animated relighting of a .relume container: one map rotated by a
// fixed step per frame, one map per frame from a list, a moved light circling the object
// (--light-orbit) or following a file of directions (--light-path), written as numbered images
// and/or a video (--video, apps/commands/relight/video_writer.hpp). Frames are relit B at a time in
// one pass over W and the residual, written as numbered images, and the run reports frames/s, the
// kernels' GB/s and, with --compare, each frame's error against the full-residual render.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/lighting.hpp>
#include <relume/relight.hpp>

#include "command_registry.hpp"
#include "commands/relight/sequence_lights.hpp"
#include "commands/relight/video_writer.hpp"
#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/json_report.hpp"
#include "core/progress.hpp"
#include "field/light_file.hpp"
#include "image/image_difference.hpp"
#include "lighting/environment_map.hpp"
#include "options/directional_light_options.hpp"
#include "options/frame_pattern.hpp"
#include "options/image_output_options.hpp"
#include "options/output_paths.hpp"
#include "options/renderer_options.hpp"
#include "options/rotation_option.hpp"
#include "relight/relight_layout.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

// --frames 2147483647 made as many light vectors before the first frame: memory ran out.
constexpr int max_sequence_frames = 100000;

void run_sequence(const SequenceOptions& options) {
  if (options.output_pattern.empty() && options.video.empty())
    throw Error("give -o PATTERN (frame images), --video FILE, or both");
  std::optional<FramePattern> pattern;
  if (!options.output_pattern.empty()) {
    pattern.emplace(options.output_pattern, options.start_number);
    check_image_output(pattern->path(0), options.image_output);
  }
  if (!options.video.empty()) {
    check_new_output(options.video);
    VideoWriter::check_target(options.video, options.video_codec);
  }
  if (options.batch < 1) throw Error("--batch must be at least 1");
  check_renderer_options(options.renderer);
  check_new_output(options.report);
  if (!options.report.empty()) check_output_file_location(options.report);
  if (pattern) {
    const fs::path folder = fs::path(pattern->path(0)).parent_path();
    if (!folder.empty()) check_output_folder_location(folder);
  }
  if (!options.video.empty()) check_output_file_location(options.video);
  const CompressedField field = read_container(options.input);
  const std::vector<LightRgb> lights = frame_lights(options, field);
  check_relight_memory(field, std::min<std::size_t>(std::size_t(options.batch), lights.size()) *
                                  (options.compare ? 2 : 1));
  if (pattern)
    for (std::size_t frame = 0; frame < lights.size(); ++frame)
      check_new_output(pattern->path(int(frame)));
  const int cap = residual_cap(options.renderer, field.lights);
  using clock = std::chrono::steady_clock;
  // Set-up apart from frames/s: uploading the field, and building the kernels, which happens on
  // the first relight of each batch size (one warm-up relight of each size used).
  const auto setup_start = clock::now();
  Relighter renderer(field, options.renderer.relighter);
  const std::size_t full = std::min<std::size_t>(options.batch, lights.size());
  for (const std::size_t size : {full, lights.size() % full})
    if (size > 0)
      renderer.relight_batch(std::vector<LightRgb>(lights.begin(), lights.begin() + size), cap);
  const double setup_seconds = std::chrono::duration<double>(clock::now() - setup_start).count();
  note(
      "relight-sequence: set-up %.2f s (field upload, kernel build, one warm-up relight per "
      "batch size), not counted in frames/s",
      setup_seconds);
  if (pattern) {
    const fs::path folder = fs::path(pattern->path(0)).parent_path();
    if (!folder.empty()) fs::create_directories(folder);
  }
  std::optional<VideoWriter> video;
  if (!options.video.empty())
    video.emplace(options.video, field.width, field.height, options.video_fps, options.video_codec);

  double relight_seconds = 0, kernel_seconds = 0, kernel_bytes = 0;
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  // From the first frame (its auto exposure, if asked), for every frame.
  std::optional<ImageWriteOptions> write;
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
    if (options.compare) references = renderer.relight_batch(batch, all_residual_entries);
    for (std::size_t b = 0; b < count; ++b) {
      const int frame = static_cast<int>(first + b);
      if (!write) {
        const bool display =
            video || !is_float_image_format(pattern->path(0)) || options.image_output.bits != 0;
        write = ImageWriteOptions{
            display ? display_exposure(options.image_output, images[b], field.mask) : 0.0,
            options.image_output.bits, options.image_output.half};
      }
      nlohmann::ordered_json record = {{"frame", frame}};
      if (pattern) {
        write_image(pattern->path(frame), images[b], *write);
        record["file"] = pattern->path(frame);
      }
      if (video) video->add_frame(images[b], write->exposure);
      if (options.compare)
        record["error"] = image_difference(images[b], references[b]).relative_squared_error;
      frames.push_back(record);
      progress.advance();
    }
  }
  progress.finish();
  if (video) {
    video->finish();
    say("wrote %s: %d frames, %s, %d frames/s", options.video.c_str(), video->frames(),
        video->codec_name().c_str(), options.video_fps);
  }

  const double fps = relight_seconds > 0 ? lights.size() / relight_seconds : 0;
  const double gbps = kernel_seconds > 0 ? 1e-9 * kernel_bytes / kernel_seconds : 0;
  say("%zu frames on %s, batch %d, residual cap %s: %.1f frames/s relighting (%.2f s), "
      "kernels %.2f GB/s",
      lights.size(), renderer.device_name().c_str(), options.batch, residual_cap_text(cap).c_str(),
      fps, relight_seconds, gbps);
  if (options.compare) {
    double worst = 0;
    for (const auto& f : frames) worst = std::max(worst, f["error"].get<double>());
    say("largest per-frame relative squared error against the full residual: %.3g", worst);
  }
  if (!options.report.empty()) {
    const nlohmann::ordered_json report = {{"device", renderer.device_name()},
                                           {"frames", lights.size()},
                                           {"batch", options.batch},
                                           {"residual_cap", cap == all_residual_entries ? -1 : cap},
                                           {"setup_seconds", setup_seconds},
                                           {"relight_seconds", relight_seconds},
                                           {"frames_per_second", fps},
                                           {"kernel_gbps", gbps},
                                           {"per_frame", frames}};
    nlohmann::ordered_json document = report;
    if (video)
      document["video"] = {{"file", options.video},
                           {"codec", video->codec_name()},
                           {"frames_per_second", options.video_fps}};
    write_json_report(options.report, document);
  }
}

const CommandRegistration registration{
    35, [](CLI::App& app) {
      auto options = std::make_shared<SequenceOptions>();
      auto* command = app.add_subcommand(
          "relight-sequence",
          "Relight a .relume container under a rotating environment, a list of maps, or a light\n"
          "moved along an orbit or a path, one image per frame.\n"
          "Example: relume relight-sequence scene.relume --light-orbit 20 --frames 72 "
          "--rotate-step 5 -o orbit/%04d.png");
      command->add_option("input", options->input, "The .relume container")->required();
      auto* env =
          command->add_option("--env", options->environment,
                              "Environment map rotated about +y by --rotate-step per frame");
      auto* list = command->add_option("--env-list", options->environment_list,
                                       "Text file naming one environment map per frame (paths "
                                       "relative to the list's folder)");
      auto* orbit = command->add_option(
          "--light-orbit", options->orbit_elevation,
          "A moved light circling the object at this elevation in degrees above the object's "
          "plane (low = raking light), starting at azimuth --rotate (degrees from +x towards +y) "
          "and turning --rotate-step per frame, for --frames frames");
      auto* path = command->add_option("--light-path", options->light_path,
                                       "A moved light following a file of directions, one "
                                       "'x y z' row per frame");
      const std::vector<CLI::Option*> sources = {env, list, orbit, path};
      for (CLI::Option* source : sources)
        for (CLI::Option* other : sources)
          if (other != source) source->excludes(other);
      add_light_color_options(*command, options->moved_light);
      command->add_option("--layout", options->layout, "Map layout: auto, latlong, angular, cross")
          ->capture_default_str();
      command
          ->add_option("--frames", options->frames,
                       "Frames to render with --env or --light-orbit (at most 100000, over an hour "
                       "at 24 frames/s: every frame's light is made before the first is relit)")
          ->check(CLI::Range(1, max_sequence_frames))
          ->capture_default_str();
      add_rotation_option(*command, options->rotate_start,
                          "Rotation of the first frame in degrees: the map's about +y, or the "
                          "orbit's azimuth");
      command
          ->add_option("--rotate-step", options->rotate_step, "Rotation added per frame, degrees")
          ->capture_default_str();
      command->add_option(
          "-o,--output", options->output_pattern,
          "Frame file pattern with one frame number, %d, %04d or #### (four digits), "
          "e.g. frames/%04d.exr or frames/####.png (optional with --video)");
      command->add_option(
          "--video", options->video,
          "Also (or only) encode the frames into this video with FFmpeg's libraries: H.264 "
          "(libx264) in .mp4/.mkv/.mov, VP9 in .webm; exposed like PNG frames");
      command->add_option("--fps", options->video_fps, "Frames per second of --video")
          ->check(CLI::Range(1, 240))
          ->capture_default_str();
      command->add_option("--codec", options->video_codec,
                          "FFmpeg encoder for --video instead of the default (e.g. mpeg4, "
                          "libvpx-vp9)");
      command
          ->add_option("--batch", options->batch,
                       "Frames relit together in one pass over the compressed data")
          ->capture_default_str();
      command
          ->add_option("--start-number", options->start_number,
                       "Number of the first frame in the file names")
          ->capture_default_str();
      add_image_output_options(*command, options->image_output);
      command->add_flag("--compare", options->compare,
                        "Also render each frame with the full residual and report the error");
      command->add_option("--report", options->report, "Write a JSON report of the run");
      add_renderer_options(*command, options->renderer);
      command->callback([options] {
        if (options->environment.empty() && options->environment_list.empty() &&
            !options->orbit_elevation && options->light_path.empty())
          throw Error(
              "give --env MAP (rotating), --env-list FILE, --light-orbit ELEVATION or "
              "--light-path FILE");
        run_sequence(*options);
      });
    }};

}  // namespace
}  // namespace relume
