// `relume publish`: writes a static web site (index.html, ES modules, manifest.json, data/*.bin)
// in which a .relume container is relit on the viewer's GPU with WebGL2, and says what each part
// of it weighs against the container.
#include <relume/residual_budget.hpp>

#include "command_registry.hpp"
#include "core/console.hpp"
#include "options/output_paths.hpp"
#include "publish/published_site.hpp"

namespace relume {
namespace {

struct PublishCommandOptions {
  std::string input;
  std::string output;
  std::string title;
  std::vector<std::string> environments;
  std::string residual = "all";
  double exposure = 0;
  int tile_size = default_tile_size;
  bool list_files = false;
};

void run_publish(const PublishCommandOptions& options) {
  check_output_folder(options.output);
  PublishOptions publish;
  publish.title = options.title;
  publish.exposure = options.exposure;
  publish.tile_size = options.tile_size;
  publish.environments.assign(options.environments.begin(), options.environments.end());
  // Entries or a percentage of the lights, as relight's --residual.
  if (options.residual != "all") publish.residual = ResidualBudget::parse(options.residual);
  const PublishReport report = publish_container(options.input, options.output, publish);
  if (options.list_files)
    for (const PublishedFile& file : report.files)
      say("  %-32s %12llu bytes", file.path.c_str(), static_cast<unsigned long long>(file.bytes));
  std::uint64_t upper_levels = 0;
  for (std::size_t level = 1; level < report.level_bytes.size(); ++level)
    upper_levels += report.level_bytes[level];
  const auto bytes = [](std::uint64_t n) { return static_cast<unsigned long long>(n); };
  say("wrote %s: %llu bytes on the wire for the full view (%.3fx the container's %llu): page "
      "%llu, manifest %llu, field %llu, level-0 tiles %llu",
      options.output.c_str(), bytes(report.full_view_bytes()),
      double(report.full_view_bytes()) / double(report.container_bytes),
      bytes(report.container_bytes), bytes(report.page_bytes), bytes(report.manifest_bytes),
      bytes(report.field_bytes), bytes(report.level_bytes.empty() ? 0 : report.level_bytes[0]));
  if (report.weight_planes_bytes > 0)
    say("  and weights %llu: the container's JPEG 2000 codestream as it is (data/weights.j2k; "
        "the page decodes it with OpenJPEG built for WebAssembly, openjpeg/ in its bytes)",
        bytes(report.weight_planes_bytes));
  say("  %zu coarser levels %llu bytes (fetched instead of level 0 when zoomed out), maps %llu "
      "bytes (each fetched when picked); residual up to %d entries per function (%llu entries)",
      report.level_bytes.empty() ? std::size_t(0) : report.level_bytes.size() - 1,
      bytes(upper_levels), bytes(report.environment_bytes), report.residual_longest_row,
      bytes(report.residual_entries));
  note("serve it with any static web server, e.g. python3 -m http.server -d %s",
       options.output.c_str());
}

const CommandRegistration registration{
    42, [](CLI::App& app) {
      auto options = std::make_shared<PublishCommandOptions>();
      auto* command = app.add_subcommand(
          "publish",
          "Write a static web site that relights a .relume container on the viewer's GPU\n"
          "(WebGL2): drag a light or turn an environment map, set exposure and the residual cap,\n"
          "zoom and pan a tile pyramid; no server-side relume.\n"
          "Example: relume publish scene.relume -o site/ --env sky.exr --title 'Carved lion' && "
          "python3 -m http.server -d site/");
      command->add_option("input", options->input, "The .relume container")->required();
      command
          ->add_option("-o,--output", options->output,
                       "Site folder (created if missing; a non-empty one is refused unless "
                       "-y/--overwrite, which replaces files of the same names)")
          ->required();
      command
          ->add_option("--env", options->environments,
                       "Environment map(s) the page offers besides the moved light, turned "
                       "about the up axis with a slider (repeat for several)")
          ->check(CLI::ExistingFile);
      command->add_option("--title", options->title,
                          "The page's title (default: the container's file name)");
      command
          ->add_option("--residual", options->residual,
                       "Residual entries kept per function: all, N, or P% of the lights (the "
                       "largest ones; the page's cap slider ends there)")
          ->capture_default_str();
      command->add_option("--exposure", options->exposure, "The page's first exposure, in stops")
          ->check(CLI::Range(-30.0, 30.0))
          ->capture_default_str();
      command
          ->add_option("--tile-size", options->tile_size,
                       "Side of the pyramid's square tiles, in pixels of their level")
          ->check(CLI::Range(8, 4096))
          ->capture_default_str();
      command->add_flag("--list", options->list_files, "List the files written and their bytes");
      command->callback([options] { run_publish(*options); });
    }};

}  // namespace
}  // namespace relume
