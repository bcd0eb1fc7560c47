// Implementation of the regions of a compressed field (field_region.hpp).
#include "publish/field_region.hpp"

#include <algorithm>
#include <relume/error.hpp>

#include "model/reconstruct_field.hpp"

namespace relume {

FieldRegions::FieldRegions(const CompressedField& field)
    : field_(field), row_of_function_(stored_row_of_function(field)) {}

CompressedField FieldRegions::region(const FieldRegion& region, int residual_cap) const {
  const CompressedField& field = field_;
  const auto last = [&](int first, int count) {
    return std::int64_t(first) + std::int64_t(region.stride) * (count - 1);
  };
  if (region.stride < 1 || region.width < 1 || region.height < 1 || region.x < 0 || region.y < 0 ||
      last(region.x, region.width) >= field.width || last(region.y, region.height) >= field.height)
    throw Error("region " + std::to_string(region.width) + " x " + std::to_string(region.height) +
                " at (" + std::to_string(region.x) + ", " + std::to_string(region.y) +
                "), stride " + std::to_string(region.stride) + ", lies outside the " +
                std::to_string(field.width) + " x " + std::to_string(field.height) + " field");
  check_residual_cap(residual_cap);
  CompressedField part;
  part.width = region.width;
  part.height = region.height;
  part.channels = field.channels;
  part.lights = field.lights;
  part.terms = field.terms;
  part.clusters = field.clusters;
  part.transform = field.transform;
  part.quantization.weight_step = field.quantization.weight_step;
  part.quantization.residual_step = field.quantization.residual_step;
  part.dark_gain_step = field.dark_gain_step;
  part.non_negative = field.non_negative;
  part.residual.row_offsets.push_back(0);
  std::vector<float> weights;
  const int channels = field.channels;
  for (int ry = 0; ry < region.height; ++ry)
    for (int rx = 0; rx < region.width; ++rx) {
      const std::int64_t pixel =
          (std::int64_t(region.y) + std::int64_t(region.stride) * ry) * field.width + region.x +
          std::int64_t(region.stride) * rx;
      const std::uint32_t part_pixel = std::uint32_t(ry * region.width + rx);
      for (int c = 0; c < channels; ++c) {
        const std::int64_t row = row_of_function_[std::size_t(pixel * channels + c)];
        if (row >= 0) {
          part.stored_function.push_back(part_pixel * channels + c);
          part.cluster.push_back(field.cluster[std::size_t(row)]);
          const float* w = field.weights.data() + row * field.terms;
          weights.insert(weights.end(), w, w + field.terms);
          const std::uint32_t begin = field.residual.row_offsets[std::size_t(row)];
          const std::uint32_t length =
              std::min(field.residual.length(std::size_t(row)), std::uint32_t(residual_cap));
          part.residual.light_index.insert(part.residual.light_index.end(),
                                           field.residual.light_index.begin() + begin,
                                           field.residual.light_index.begin() + begin + length);
          part.residual.values.insert(part.residual.values.end(),
                                      field.residual.values.begin() + begin,
                                      field.residual.values.begin() + begin + length);
          part.residual.row_offsets.push_back(std::uint32_t(part.residual.values.size()));
        } else if (row != unstored_row && c == 0) {
          // dark_model_row(d, channels, 0) = -2 - d * channels: the pixel is dark pixel d.
          const std::size_t dark = std::size_t(-2 - row) / std::size_t(channels);
          part.dark_pixels.push_back(part_pixel);
          for (int g = 0; g < channels && !field.dark_gains.empty(); ++g)
            part.dark_gains.push_back(field.dark_gains[dark * channels + g]);
        }
      }
    }
  part.weights =
      Eigen::Map<const RowMatrixF>(weights.data(), Eigen::Index(part.stored_rows()), field.terms);
  return part;
}

}  // namespace relume
