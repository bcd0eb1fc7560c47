// `relume synth`: renders a synthetic OLAT set with exact ground truth (spheres on a ground disc,
// see lib/synth/synthetic_scene.hpp) and writes it as a field folder that every other command
// reads.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <relume/error.hpp>
#include <relume/field.hpp>
#include <string>

#include "command_registry.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/memory_budget.hpp"
#include "core/progress.hpp"
#include "field/field_folder_writer.hpp"
#include "options/output_paths.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

struct SynthArguments {
  std::string output;
  std::string size;
  SynthOptions options;
  bool hemisphere = false;
};

// "WxH" (also "W*H" or "WXH") into width and height.
void parse_size(const std::string& text, SynthOptions& options) {
  const auto separator = text.find_first_of("xX*");
  std::size_t width_end = 0, height_end = 0;
  try {
    if (separator == std::string::npos) throw std::invalid_argument(text);
    const std::string width = text.substr(0, separator), height = text.substr(separator + 1);
    options.width = std::stoi(width, &width_end);
    options.height = std::stoi(height, &height_end);
    if (width_end != width.size() || height_end != height.size()) throw std::invalid_argument(text);
  } catch (const std::logic_error&) {
    throw Error("--size expects WIDTHxHEIGHT in pixels (for example 640x640), got '" + text + "'");
  }
}

void run_synth(const SynthArguments& arguments) {
  SynthOptions options = arguments.options;
  if (!arguments.size.empty()) parse_size(arguments.size, options);
  if (arguments.hemisphere) options.layout = LightLayout::hemisphere;
  validate_synth_options(options);
  check_output_folder(arguments.output);

  // Rendered and written strip by strip: the field need not fit in memory, a row (rendered, and
  // the writer's copy) and the mask must; strips take at most a quarter of the budget.
  const std::uint64_t row_bytes =
      std::uint64_t(options.width) * 3 * std::uint64_t(options.lights) * sizeof(float);
  check_memory_need(2 * row_bytes + std::uint64_t(options.width) * std::uint64_t(options.height),
                    "a synthetic field of " + std::to_string(options.width) + "x" +
                        std::to_string(options.height) + " pixels and " +
                        std::to_string(options.lights) + " lights, written a row at a time,");
  StripLimits limits;
  limits.strip_bytes = std::size_t(
      std::clamp<std::uint64_t>(memory_budget().bytes / 4, row_bytes, limits.strip_bytes));
  const SyntheticRenderer renderer(options);
  const ReflectanceField& header = renderer.header();
  const FieldFolderLayout layout{header.width,      header.height,      header.channels,
                                 header.directions, header.intensities, header.mask};
  note("synth: rendering and writing %d EXR images to %s", options.lights,
       arguments.output.c_str());
  ProgressReporter progress("synth: rendering and writing", std::uint64_t(options.height));
  double render_seconds = 0;
  const auto start = std::chrono::steady_clock::now();
  // Into a temporary folder renamed at the end: a failure (a full disk) exposes nothing.
  write_folder_atomically(arguments.output, [&](const std::filesystem::path& temp) {
    write_field_folder_in_strips(
        temp, layout,
        [&](int first_row, int rows, int first_light, int lights, float* values) {
          const auto render_start = std::chrono::steady_clock::now();
          const ReflectanceField strip = renderer.render_rows(first_row, rows);
          render_seconds +=
              std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start)
                  .count();
          fill_strip_from(strip, first_row, first_row, rows, first_light, lights, values);
          if (first_light == 0) progress.advance(std::uint64_t(rows));
        },
        limits);
  });
  progress.finish();
  const double write_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
      render_seconds;

  say("synth: %dx%d, %d lights (%s), seed %llu -> %s: rendered in %.2f s, written in %.2f s",
      options.width, options.height, options.lights,
      options.layout == LightLayout::sphere ? "sphere" : "hemisphere",
      static_cast<unsigned long long>(options.seed), arguments.output.c_str(), render_seconds,
      write_seconds);
}

const CommandRegistration registration(10, [](CLI::App& app) {
  auto arguments = std::make_shared<SynthArguments>();
  CLI::App* command = app.add_subcommand(
      "synth",
      "Render a synthetic OLAT set with exact ground truth: coloured spheres (diffuse, glossy,\n"
      "near-mirror) on a checkered ground with cast shadows, one EXR per distant light, plus\n"
      "filenames.txt, light_directions.txt, light_intensities.txt and mask.png.");
  command->add_option("-o,--output", arguments->output, "Folder to write the field into")
      ->required();
  auto* size = command->add_option("--size", arguments->size,
                                   "Image size as WIDTHxHEIGHT (default 640x640)");
  command->add_option("--width", arguments->options.width, "Image width in pixels")
      ->capture_default_str()
      ->excludes(size);
  command->add_option("--height", arguments->options.height, "Image height in pixels")
      ->capture_default_str()
      ->excludes(size);
  command
      ->add_option("--lights", arguments->options.lights,
                   "Number of lights, spread near-uniformly (the paper's Light Stage has 253)")
      ->capture_default_str();
  command->add_flag("--hemisphere", arguments->hemisphere,
                    "Put the lights on the front hemisphere only (z >= 0, towards the camera, as "
                    "in photometric stereo) instead of the whole sphere");
  command
      ->add_option("--seed", arguments->options.seed,
                   "Seed of the scene layout (sphere positions, sizes, colours, materials)")
      ->capture_default_str();
  command
      ->add_option("--samples", arguments->options.samples_per_axis,
                   "Supersampling: camera rays per pixel along each axis (N*N per pixel)")
      ->capture_default_str();
  command
      ->add_option("--threads", arguments->options.threads,
                   "Worker threads (default 0 = all cores)")
      ->capture_default_str();
  command->callback([arguments] { run_synth(*arguments); });
});

}  // namespace
}  // namespace relume
