// `relume publish`: a folder that any static web server can serve, in which the page (web/)
// relights a compressed field on the viewer's GPU with WebGL2. It holds the page's files, the
// manifest (manifest.json: the title, the field's shape, the lighting entries, the tile pyramid
// and the files' arrays), the field's files in the web layout (data/field.bin, data/tiles/, and
// for a one-basis field data/weights.j2k: publish/web_layout.hpp) and the environment maps
// (data/env/: publish/web_environment.hpp). The page's JPEG 2000 decoder (web/openjpeg/) goes
// only into sites with data/weights.j2k.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/residual_budget.hpp>
#include <string>
#include <vector>

#include "publish/web_layout.hpp"

namespace relume {

struct PublishOptions {
  std::string title;  // empty: the container's file name
  // Residual entries kept per function (the largest; none given: all); the page's cap slider
  // ends there.
  std::optional<ResidualBudget> residual;
  double exposure = 0;                              // the page's first exposure, in stops
  std::vector<std::filesystem::path> environments;  // maps the page offers besides the light
  int tile_size = default_tile_size;
};

struct PublishedFile {
  std::string path;  // relative to the site folder
  std::uint64_t bytes = 0;
};

struct PublishReport {
  std::vector<PublishedFile> files;  // in writing order: page, manifest, field, tiles, maps
  std::uint64_t container_bytes = 0;
  std::uint64_t page_bytes = 0;  // web/* files
  std::uint64_t manifest_bytes = 0;
  std::uint64_t field_bytes = 0;  // data/field.bin
  // data/weights.j2k: the container's JPEG 2000 codestream of the weights (one-basis fields),
  // which the page decodes; 0 when the tiles hold the weights.
  std::uint64_t weight_planes_bytes = 0;
  std::vector<std::uint64_t> level_bytes;  // the tiles of each pyramid level
  std::uint64_t environment_bytes = 0;     // data/env/*.bin
  int residual_longest_row = 0;            // entries of the longest residual row kept
  std::uint64_t residual_entries = 0;
  // What a browser fetches to show the whole field at full resolution: the page, the manifest,
  // data/field.bin, data/weights.j2k and the tiles of level 0 (a map adds its file when
  // picked).
  std::uint64_t full_view_bytes() const {
    return page_bytes + manifest_bytes + field_bytes + weight_planes_bytes +
           (level_bytes.empty() ? 0 : level_bytes[0]);
  }
};

// Writes the site of the container at `container` into `site` (atomically: a failure leaves no
// half-written folder; an existing folder gets its files of the same names replaced). Throws
// Error for an unreadable container or map, or a field the page cannot relight (not 1 or 3
// channels).
PublishReport publish_container(const std::filesystem::path& container,
                                const std::filesystem::path& site, const PublishOptions& options);

}  // namespace relume
