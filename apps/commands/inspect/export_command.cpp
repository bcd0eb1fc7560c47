// `relume export IN.relume --to npz OUT.npz`: the compressed field's arrays for tools outside
// relume (lib/export/npz_export.hpp lists them): numpy.load reads the archive, no pickle needed.
#include <filesystem>
#include <memory>
#include <relume/error.hpp>

#include "command_registry.hpp"
#include "container/container.hpp"
#include "core/console.hpp"
#include "export/npz_export.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

struct ExportOptions {
  std::string input;
  std::string format = "npz";
  std::string output;
};

void run_export(const ExportOptions& options) {
  check_new_output(options.output);
  const CompressedField field = read_container(options.input);
  write_compressed_field_npz(options.output, field);
  say("wrote %s: %zu stored rows, %d clusters x %d terms x %d lights, %zu residual entries (%ju "
      "bytes)",
      options.output.c_str(), field.stored_rows(), field.clusters, field.terms, field.lights,
      field.residual.nonzeros(), std::uintmax_t(std::filesystem::file_size(options.output)));
}

const CommandRegistration registration{
    47, [](CLI::App& app) {
      auto options = std::make_shared<ExportOptions>();
      auto* command = app.add_subcommand(
          "export",
          "Export a .relume container's arrays for other tools: --to npz writes a NumPy .npz\n"
          "(clusters, W, F, the residual as CSR, the dark model, lights, intensities, mask,\n"
          "transform, quantization; the archive's 'description' says how they rebuild the field)\n"
          "Example: relume export scene.relume --to npz scene.npz, then in Python\n"
          "         d = numpy.load('scene.npz'); d['W'][0] @ d['F'][d['cluster'][0]]");
      command->add_option("input", options->input, "The .relume container")->required();
      command->add_option("--to", options->format, "Format: npz (NumPy)")
          ->check(CLI::IsMember({"npz"}))
          ->capture_default_str();
      command->add_option("output", options->output, "Output file (OUT.npz)")->required();
      command->callback([options] { run_export(*options); });
    }};

}  // namespace
}  // namespace relume
