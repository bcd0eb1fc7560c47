// Implementation of compressed field strips (see compressed_field_rows.hpp).
#include "model/compressed_field_rows.hpp"

#include <algorithm>
#include <relume/error.hpp>
#include <string>

namespace relume {

CompressedField compressed_rows(const CompressedField& field, int first_row, int rows) {
  if (first_row < 0 || rows < 0 || first_row + rows > field.height)
    throw Error("rows " + std::to_string(first_row) + " to " + std::to_string(first_row + rows) +
                " are outside the compressed field's " + std::to_string(field.height));
  CompressedField strip;
  strip.width = field.width;
  strip.height = rows;
  strip.channels = field.channels;
  strip.lights = field.lights;
  strip.terms = field.terms;
  strip.clusters = field.clusters;
  strip.transform = field.transform;
  strip.directions = field.directions;
  strip.intensities = field.intensities;
  strip.bases = field.bases;
  strip.quantization = field.quantization;
  strip.non_negative = field.non_negative;
  const std::size_t first_pixel = std::size_t(first_row) * field.width;
  const std::size_t end_pixel = first_pixel + std::size_t(rows) * field.width;
  strip.mask.assign(field.mask.begin() + std::ptrdiff_t(first_pixel),
                    field.mask.begin() + std::ptrdiff_t(end_pixel));
  const auto dark_begin =
      std::lower_bound(field.dark_pixels.begin(), field.dark_pixels.end(), first_pixel);
  const auto dark_end = std::lower_bound(dark_begin, field.dark_pixels.end(), end_pixel);
  for (auto q = dark_begin; q != dark_end; ++q)
    strip.dark_pixels.push_back(std::uint32_t(*q - first_pixel));
  if (!strip.dark_pixels.empty()) strip.dark = field.dark;
  if (!field.dark_gains.empty() && !strip.dark_pixels.empty()) {
    const auto channels = std::ptrdiff_t(field.channels);
    strip.dark_gains.assign(
        field.dark_gains.begin() + (dark_begin - field.dark_pixels.begin()) * channels,
        field.dark_gains.begin() + (dark_end - field.dark_pixels.begin()) * channels);
    strip.dark_gain_step = field.dark_gain_step;
  }

  const std::size_t first_function = first_pixel * field.channels;
  const std::size_t end_function = end_pixel * field.channels;
  const std::size_t begin = std::size_t(
      std::lower_bound(field.stored_function.begin(), field.stored_function.end(), first_function) -
      field.stored_function.begin());
  const std::size_t end =
      std::size_t(std::lower_bound(field.stored_function.begin() + std::ptrdiff_t(begin),
                                   field.stored_function.end(), end_function) -
                  field.stored_function.begin());
  for (std::size_t r = begin; r < end; ++r)
    strip.stored_function.push_back(std::uint32_t(field.stored_function[r] - first_function));
  strip.cluster.assign(field.cluster.begin() + std::ptrdiff_t(begin),
                       field.cluster.begin() + std::ptrdiff_t(end));
  strip.weights = field.weights.middleRows(Eigen::Index(begin), Eigen::Index(end - begin));
  const ResidualRows& e = field.residual;
  const std::uint32_t first_entry = e.row_offsets[begin], end_entry = e.row_offsets[end];
  for (std::size_t r = begin; r <= end; ++r)
    strip.residual.row_offsets.push_back(e.row_offsets[r] - first_entry);
  strip.residual.light_index.assign(e.light_index.begin() + first_entry,
                                    e.light_index.begin() + end_entry);
  strip.residual.values.assign(e.values.begin() + first_entry, e.values.begin() + end_entry);
  return strip;
}

void append_compressed_rows(CompressedField& field, const CompressedField& strip) {
  if (field.height == 0) {
    field = strip;
    return;
  }
  if (strip.width != field.width || strip.channels != field.channels ||
      strip.lights != field.lights || strip.terms != field.terms ||
      strip.clusters != field.clusters || strip.transform != field.transform)
    throw Error("cannot stack compressed strips of different shapes");
  const std::uint32_t pixel_offset = std::uint32_t(std::size_t(field.height) * field.width);
  const std::uint32_t function_offset = pixel_offset * std::uint32_t(field.channels);
  field.mask.insert(field.mask.end(), strip.mask.begin(), strip.mask.end());
  const bool field_gains = !field.dark_gains.empty() || field.dark_pixels.empty();
  const bool strip_gains = !strip.dark_gains.empty() || strip.dark_pixels.empty();
  if (field_gains != strip_gains && !field.dark_pixels.empty() && !strip.dark_pixels.empty())
    throw Error("cannot stack a compressed strip with dark gains and one without");
  field.dark_gains.insert(field.dark_gains.end(), strip.dark_gains.begin(), strip.dark_gains.end());
  if (!strip.dark_gains.empty()) field.dark_gain_step = strip.dark_gain_step;
  for (const std::uint32_t q : strip.dark_pixels) field.dark_pixels.push_back(pixel_offset + q);
  if (field.dark.empty()) field.dark = strip.dark;
  for (const std::uint32_t p : strip.stored_function)
    field.stored_function.push_back(function_offset + p);
  field.cluster.insert(field.cluster.end(), strip.cluster.begin(), strip.cluster.end());
  const Eigen::Index old_rows = field.weights.rows();
  field.weights.conservativeResize(old_rows + strip.weights.rows(), field.terms);
  field.weights.bottomRows(strip.weights.rows()) = strip.weights;
  ResidualRows& e = field.residual;
  if (e.row_offsets.empty()) e.row_offsets.push_back(0);
  const std::uint32_t entry_offset = e.row_offsets.back();
  for (std::size_t r = 1; r < strip.residual.row_offsets.size(); ++r)
    e.row_offsets.push_back(entry_offset + strip.residual.row_offsets[r]);
  e.light_index.insert(e.light_index.end(), strip.residual.light_index.begin(),
                       strip.residual.light_index.end());
  e.values.insert(e.values.end(), strip.residual.values.begin(), strip.residual.values.end());
  field.non_negative = field.non_negative && strip.non_negative;
  field.height += strip.height;
}

}  // namespace relume
