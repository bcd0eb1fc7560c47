// Implementation of the published site (published_site.hpp): the manifest, the data files and
// the page's files, written into one folder atomically.
#include "publish/published_site.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <relume/version.hpp>

#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "publish/web_assets.hpp"
#include "publish/web_environment.hpp"
#include "publish/web_lighting.hpp"

namespace relume {
namespace {

// The page's JPEG 2000 decoder (web/openjpeg/), needed only by fields with weight planes.
const std::string decoder_folder = "openjpeg/";

}  // namespace

PublishReport publish_container(const std::filesystem::path& container,
                                const std::filesystem::path& site, const PublishOptions& options) {
  if (!std::isfinite(options.exposure))
    throw Error("publish: the exposure must be a finite number of stops");
  const CompressedField field = read_container(container);
  if (field.channels != 1 && field.channels != 3)
    throw Error("cannot publish " + container.string() + ": it has " +
                std::to_string(field.channels) + " channels (the page relights 1 or 3)");
  const WebLayout layout = lay_out_for_web(
      field, options.residual ? options.residual->entries_for(field.lights) : all_residual_entries,
      options.tile_size);
  std::vector<WebEnvironment> environments;
  for (const auto& map : options.environments)
    environments.push_back(lay_out_environment(map, int(environments.size())));

  nlohmann::ordered_json manifest;
  manifest["format"] = "relume-web";
  manifest["version"] = 1;
  manifest["generator"] = "relume " + version();
  manifest["title"] = options.title.empty() ? container.filename().string() : options.title;
  manifest["exposure"] = options.exposure;
  manifest["field"] = layout.field;
  manifest["light_cover"] = light_cover_json(field.directions);
  manifest["srgb_thresholds"] = srgb_thresholds_json();
  manifest["field_file"] = layout.field_file;
  manifest["tiles"] = layout.tiles;
  if (!layout.weight_planes.is_null()) manifest["weight_planes"] = layout.weight_planes;
  manifest["environments"] = nlohmann::ordered_json::array();
  for (const WebEnvironment& environment : environments)
    manifest["environments"].push_back(environment.entry);
  const std::string manifest_text = manifest.dump() + "\n";

  PublishReport report;
  report.container_bytes = std::filesystem::file_size(container);
  report.residual_longest_row = layout.field["residual_longest_row"].get<int>();
  report.residual_entries = layout.field["residual_entries"].get<std::uint64_t>();
  report.manifest_bytes = manifest_text.size();
  write_folder_atomically(site, [&](const std::filesystem::path& folder) {
    const auto write = [&](const std::string& path, const std::string& bytes) {
      std::filesystem::create_directories((folder / path).parent_path());
      write_file_atomically(folder / path, bytes);
      report.files.push_back({path, bytes.size()});
    };
    for (const auto& [name, bytes] : web_assets()) {
      if (name.starts_with(decoder_folder) && layout.weight_planes.is_null()) continue;
      write(name, bytes);
      report.page_bytes += bytes.size();
    }
    write("manifest.json", manifest_text);
    for (const WebFile& file : layout.files) {
      write(file.path, file.bytes);
      if (file.level == field_file_level) {
        report.field_bytes += file.bytes.size();
        continue;
      }
      if (file.level == weight_planes_level) {
        report.weight_planes_bytes += file.bytes.size();
        continue;
      }
      if (report.level_bytes.size() <= std::size_t(file.level))
        report.level_bytes.resize(file.level + 1);
      report.level_bytes[file.level] += file.bytes.size();
    }
    for (const WebEnvironment& environment : environments) {
      write(environment.file.path, environment.file.bytes);
      report.environment_bytes += environment.file.bytes.size();
    }
  });
  return report;
}

}  // namespace relume
