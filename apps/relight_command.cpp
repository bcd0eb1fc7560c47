// `relume relight`: renders one relit image of a reflectance field under a light vector file or
// an environment map. A .relume container is relit with OpenCL (or the C++ reference with --cpu);
// an uncompressed field (folder or .lp) by the double-precision reference, the ground truth the
// compressed paths are tested against.
#include <filesystem>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <relume/relight.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "light_source_options.hpp"
#include "renderer_options.hpp"

namespace relume {
namespace {

struct RelightOptions {
  std::string input;
  LightSourceOptions light_source;
  RendererOptions renderer;
  std::string output;
  double exposure = 0;
  bool srgb_input = false;
  unsigned threads = 0;
};

void relight_container(const RelightOptions& options) {
  const CompressedField field = read_container(options.input);
  const LightRgb lights = resolve_light_vector(options.light_source, field.directions);
  check_relight_memory(field, 1);
  Relighter renderer(field, options.renderer.relighter);
  const int cap = residual_cap(options.renderer, field.lights);
  const Image image = renderer.relight(lights, cap);
  detail("relight: %s, residual cap %s, kernels %.2f ms", renderer.device_name().c_str(),
         cap == full_residual ? "all" : std::to_string(cap).c_str(),
         1e3 * renderer.last_kernel_seconds());
  write_image(options.output, image, {options.exposure});
}

void run_relight(const RelightOptions& options) {
  check_output_file_location(options.output);
  check_renderer_options(options.renderer);
  if (std::filesystem::path(options.input).extension() == ".relume") {
    relight_container(options);
    return;
  }
  FieldLoadOptions load;
  load.threads = options.threads;
  if (options.srgb_input) load.image.eight_bit = EightBitEncoding::srgb;
  const ReflectanceField field = load_field(options.input, load);
  const LightRgb lights = resolve_light_vector(options.light_source, field.directions);
  const Image image = relight_field(field, lights, options.threads);
  write_image(options.output, image, {options.exposure});
}

const CommandRegistration registration{
    30, [](CLI::App& app) {
      auto options = std::make_shared<RelightOptions>();
      auto* command = app.add_subcommand(
          "relight", "Relight a reflectance field under an environment map or a light vector file");
      command
          ->add_option(
              "input", options->input,
              "A .relume container, or an uncompressed field: a folder (DiLiGenT layout) or an "
              "RTI .lp file")
          ->required();
      add_light_source_options(*command, options->light_source);
      add_renderer_options(*command, options->renderer);
      command
          ->add_option("-o,--output", options->output,
                       "Output image: .exr/.hdr/.tif are linear float, .png/.jpg are exposed and "
                       "sRGB-encoded")
          ->required();
      command->add_option("--exposure", options->exposure,
                          "Exposure in stops applied to 8-bit outputs (default 0)");
      command->add_flag(
          "--srgb", options->srgb_input,
          "Decode 8-bit input images of an uncompressed field as sRGB (default: linear)");
      command->add_option("--threads", options->threads, "Worker threads (default: all cores)");
      command->callback([options] { run_relight(*options); });
    }};

}  // namespace
}  // namespace relume
