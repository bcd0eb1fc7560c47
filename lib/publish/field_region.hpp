// Regions of a compressed field as compressed fields of their own: the tiles of the published
// page's pyramid (publish/web_layout.hpp). A region takes every `stride`-th pixel of a
// rectangle (stride 1: the rectangle itself; stride 2^l: level l of the pyramid, the pixel at
// the top-left of each 2^l x 2^l block), with each function's stored row, cluster, weights and
// residual (cut to a cap), and its dark pixels with their gains.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

struct FieldRegion {
  int x = 0, y = 0;           // the first pixel, in the field's pixels
  int stride = 1;             // pixels of the field between neighbouring pixels of the region
  int width = 0, height = 0;  // in pixels of the region
};

class FieldRegions {
 public:
  // `field` must be validated and outlive this object.
  explicit FieldRegions(const CompressedField& field);

  // The region's compressed field: the field's lights, terms, clusters, transform and value
  // steps; no bases, mask, directions or dark model (the field's own serve every region). Its
  // function p = (y' * width + x') * channels + c is the field's function of pixel
  // (x + stride x', y + stride y'). Residual rows keep at most `residual_cap` entries. Throws
  // Error for a region outside the field.
  CompressedField region(const FieldRegion& region, int residual_cap) const;

 private:
  const CompressedField& field_;
  std::vector<std::int64_t> row_of_function_;  // stored_row_of_function(field)
};

}  // namespace relume
