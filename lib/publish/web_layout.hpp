// The web layout of a compressed field: the files the published page (web/) fetches, a pyramid of
// tiles so that a large capture opens with the few tiles the window shows, and the manifest
// entries that describe them.
//
// Pyramid. Level l holds every 2^l-th pixel of every 2^l-th row (the top-left pixel of each
// 2^l x 2^l block), level 0 the whole field; the top level is the first whose image fits one
// tile. Each level is cut into tiles of tile_size x tile_size of its pixels (fewer at the right
// and bottom edges); tile (column, row) of level l holds level pixels [column * tile_size, ...)
// x [row * tile_size, ...), field pixels from (column, row) * tile_size * 2^l every 2^l pixels.
// The page fetches the tiles of the level whose pixels are nearest the screen's in size that
// the view shows. Levels above 0 add a third to what is stored, nothing to what a full view
// fetches.
//
// Files (bundles, publish/web_bundle.hpp):
//   data/field.bin                      bases int16 | float32 (clusters x terms x lights,
//                                       F^k[j][i]; int16: times basis_scales[k * terms + j], as
//                                       the container quantizes them), basis_scales float32 (with
//                                       int16 bases), dark_model float32 (channels x lights; when
//                                       any pixel is dark); all in the field's basis
//   data/tiles/L/C_R.bin                the tile's region (publish/field_region.hpp):
//     stored_functions  uint8           bit f % 8 of byte f / 8: function f = pixel * channels +
//                                       channel has a stored row; the n-th set bit is row n
//     clusters          uint8 | uint16  per stored row
//     weights           med16 | float32 (not with weight planes) stored rows x terms; med16:
//                                       quantized weights (times weight_step) as the container
//                                       stores them, the errors modulo 2^16 of the median edge
//                                       detector's prediction from the left, upper and upper-left
//                                       pixels' rows of the same channel
//                                       (container/weight_prediction.hpp), in the tile
//     residual_lengths  uint8..uint32   per stored row: entries kept (at most the cap)
//     residual_lights   uint8 | uint16  the kept entries, row after row: light index
//     residual_values   int16 | float32 the same: value (int16: times residual_step)
//     dark_pixels       uint8           (fields with dark pixels) bit set over the tile's pixels
//     dark_gains        int16           (fields with gains) per dark pixel and channel, times
//                                       dark_gain_step
//   data/weights.j2k                    (one-basis fields, whose container codes W as JPEG 2000
//                                       planes: model/weight_planes.hpp) the container's
//                                       codestream as it is; the page decodes it whole, once, with
//                                       OpenJPEG built for WebAssembly (web/openjpeg/), and gives
//                                       each tile its weights from the planes
//                                       (web/weight_planes.js)
#pragma once

#include <nlohmann/json.hpp>
#include <relume/compressed_field.hpp>
#include <string>
#include <vector>

namespace relume {

inline constexpr int default_tile_size = 256;

inline constexpr int field_file_level = -1;     // WebFile::level of data/field.bin
inline constexpr int weight_planes_level = -2;  // WebFile::level of data/weights.j2k

struct WebFile {
  std::string path;  // relative to the site, e.g. "data/tiles/0/1_2.bin"
  std::string bytes;
  int level = field_file_level;  // the pyramid level of a tile, or one of the two above
};

struct WebLayout {
  nlohmann::ordered_json field;  // the manifest's "field": sizes, transform, steps, residual kept
  nlohmann::ordered_json tiles;  // the manifest's "tiles": size, levels, file pattern, arrays
  nlohmann::ordered_json field_file;  // the manifest's "field_file": path and arrays
  // The manifest's "weight_planes": path, planes and step of data/weights.j2k; null when the
  // tiles hold the weights.
  nlohmann::ordered_json weight_planes;
  std::vector<WebFile> files;
};

// The layout of `field` with at most `residual_cap` entries of each residual row (the largest:
// rows are sorted). Throws Error for an inconsistent field, a negative cap or a tile size
// below 8.
WebLayout lay_out_for_web(const CompressedField& field, int residual_cap,
                          int tile_size = default_tile_size);

}  // namespace relume
