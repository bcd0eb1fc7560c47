// `relume relight`: renders one relit image of a reflectance field under a light vector file, an
// environment map or a moved light. A .relume container is relit with OpenCL (or the C++ reference
// with --cpu); an uncompressed field (folder or .lp) by the double-precision reference, the ground
// truth the compressed paths are tested against. Both are black outside the object mask (the
// folder's mask.png or --mask FILE) unless --no-mask keeps an uncompressed field's background.
#include <algorithm>
#include <filesystem>
#include <relume/error.hpp>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <relume/relight.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "field/load_with_progress.hpp"
#include "field/mask_file.hpp"
#include "options/field_input_options.hpp"
#include "options/image_output_options.hpp"
#include "options/light_source_options.hpp"
#include "options/output_paths.hpp"
#include "options/renderer_options.hpp"
#include "relight/relight_layout.hpp"

namespace relume {
namespace {

struct RelightOptions {
  std::string input;
  LightSourceOptions light_source;
  RendererOptions renderer;
  FieldInputOptions field_input;
  std::string output;
  ImageOutputOptions image_output;
  unsigned threads = 0;
};

// Black outside the mask (mask: width * height, 1 = inside), as a compressed field relights
// the functions it does not store.
void black_outside(Image& image, const std::vector<std::uint8_t>& mask) {
  for (std::size_t p = 0; p < mask.size(); ++p)
    if (!mask[p])
      for (int c = 0; c < image.channels; ++c) image.pixels[p * image.channels + c] = 0;
}

void relight_container(const RelightOptions& options) {
  const CompressedField field = read_container(options.input);
  if (options.field_input.no_mask &&
      std::find(field.mask.begin(), field.mask.end(), 0) != field.mask.end())
    throw Error(options.input +
                " stores only the pixels inside its mask: --no-mask cannot bring the background "
                "back (compress with --no-mask to keep it)");
  const LightRgb lights = resolve_light_vector(options.light_source, field.directions);
  check_relight_memory(field, 1);
  Relighter renderer(field, options.renderer.relighter);
  const int cap = residual_cap(options.renderer, field.lights);
  Image image = renderer.relight(lights, cap);
  std::vector<std::uint8_t> mask = field.mask;
  if (!options.field_input.mask_file.empty()) {
    mask = read_mask(options.field_input.mask_file, field.width, field.height);
    black_outside(image, mask);
  }
  detail("relight: %s, residual cap %s, kernels %.2f ms, %llu negative values set to 0",
         renderer.device_name().c_str(), residual_cap_text(cap).c_str(),
         1e3 * renderer.last_kernel_seconds(),
         static_cast<unsigned long long>(renderer.last_projected_values()));
  write_image(options.output, image,
              resolve_image_output(options.output, options.image_output, image, mask));
}

void run_relight(const RelightOptions& options) {
  check_new_output(options.output);
  check_image_output(options.output, options.image_output);
  check_output_file_location(options.output);
  check_renderer_options(options.renderer);
  if (std::filesystem::path(options.input).extension() == ".relume") {
    relight_container(options);
    return;
  }
  const ReflectanceField field = load_field_with_progress(
      options.input, input_load_options(options.input, options.field_input, options.threads));
  const LightRgb lights = resolve_light_vector(options.light_source, field.directions);
  Image image = relight_field(field, lights, options.threads);
  black_outside(image, field.mask);
  write_image(options.output, image,
              resolve_image_output(options.output, options.image_output, image, field.mask));
}

const CommandRegistration registration{
    30, [](CLI::App& app) {
      auto options = std::make_shared<RelightOptions>();
      auto* command = app.add_subcommand(
          "relight",
          "Relight a reflectance field under an environment map, a light vector file or a light\n"
          "moved to any direction between the captured ones.\n"
          "Example: relume relight scene.relume --light-dir 0.6,0.4,0.7 --spread 5 -o raking.png");
      command
          ->add_option(
              "input", options->input,
              "A .relume container, or an uncompressed field: a folder (DiLiGenT layout) or an "
              "RTI .lp file")
          ->required();
      add_light_source_options(*command, options->light_source);
      add_renderer_options(*command, options->renderer);
      add_field_input_options(*command, options->field_input);
      command
          ->add_option("-o,--output", options->output,
                       "Output image: .exr/.hdr/.tif are linear float (--half: EXR as half), "
                       ".png/.jpg (and .tif with --bits) are exposed and sRGB-encoded")
          ->required();
      add_image_output_options(*command, options->image_output);
      command->add_option("--threads", options->threads, "Worker threads (default: all cores)");
      command->callback([options] { run_relight(*options); });
    }};

}  // namespace
}  // namespace relume
