// `relume decompress`: reconstructs the reflectance field a .relume container stands for
// (W F + the residual, optionally cut to N entries per function, back in the light basis) and
// writes it as a field folder that `relume` reads again: one EXR per light, filenames.txt,
// light_directions.txt, light_intensities.txt and mask.png, strip by strip of scanlines so that
// the float32 field is never whole in memory.
#include <cstdio>
#include <memory>
#include <relume/field.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/memory_budget.hpp"
#include "model/reconstructed_folder.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

struct DecompressOptions {
  std::string input;
  std::string output;
  int residual = all_residual_entries;
};

void run_decompress(const DecompressOptions& options) {
  check_output_folder(options.output);
  const CompressedField compressed = read_container(options.input);
  check_memory_need(reconstructed_folder_memory(compressed),
                    "decompressing " + options.input + " (one strip of pixels under all " +
                        std::to_string(compressed.lights) + " lights at a time)");
  // Strip by strip into a temporary folder renamed at the end: a failure (a full disk) exposes
  // nothing, and the float32 field is never whole in memory.
  write_folder_atomically(options.output, [&](const std::filesystem::path& temp) {
    write_reconstructed_folder(temp, compressed, options.residual);
  });
  const std::string residual =
      options.residual == all_residual_entries
          ? "complete"
          : "cut to " + std::to_string(options.residual) + " entries per function";
  say("wrote %s: %d x %d pixels, %d channels, %d lights, residual %s", options.output.c_str(),
      compressed.width, compressed.height, compressed.channels, compressed.lights,
      residual.c_str());
}

const CommandRegistration registration{
    45, [](CLI::App& app) {
      auto options = std::make_shared<DecompressOptions>();
      auto* command = app.add_subcommand(
          "decompress",
          "Reconstruct the reflectance field of a .relume container and write it as a field folder "
          "(one EXR per light plus light and mask files) that relume reads again");
      command->add_option("input", options->input, "The .relume container")->required();
      command
          ->add_option("-o,--output", options->output,
                       "Output folder (created if missing; a non-empty one is refused unless "
                       "-y/--overwrite, which replaces files of the same names)")
          ->required();
      command
          ->add_option("--residual", options->residual,
                       "Keep at most N residual entries per function, the largest ones (default: "
                       "all that are stored)")
          ->check(CLI::NonNegativeNumber);
      command->callback([options] { run_decompress(*options); });
    }};

}  // namespace
}  // namespace relume
