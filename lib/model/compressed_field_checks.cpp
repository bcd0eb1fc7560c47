// Implementation of the CompressedField consistency checks (see compressed_field_checks.hpp).
#include "model/compressed_field_checks.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <vector>

#include "core/value_scans.hpp"

namespace relume {
namespace {

void check_finite_rows(const LightRgb& rows, const std::string& what, const std::string& where) {
  for (Eigen::Index i = 0; i < rows.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(rows(i, c)))
        throw Error(where + ": " + what + " of light " + std::to_string(i) + " component " +
                    std::to_string(c) + " is " + std::to_string(rows(i, c)) + ", expected finite");
}

}  // namespace

std::string stored_row_name(std::size_t row) { return "stored row " + std::to_string(row); }

void check_dimensions(const CompressedField& field, const std::string& where) {
  if (field.width < 1 || field.height < 1 || field.channels < 1 || field.lights < 1 ||
      field.terms < 0 || field.clusters < 0)
    throw Error(
        where + ": invalid dimensions " + std::to_string(field.width) + "x" +
        std::to_string(field.height) + "x" + std::to_string(field.channels) + ", " +
        std::to_string(field.lights) + " lights, " + std::to_string(field.terms) + " terms, " +
        std::to_string(field.clusters) +
        " clusters (expected width, height, channels, lights >= 1 and terms, clusters >= 0)");
  if (std::uint64_t(field.functions()) > max_compressed_functions)
    throw Error(where + ": " + std::to_string(field.functions()) +
                " functions is more than the 2^32 a container can index");
  if (field.transform != BasisTransform::identity && field.transform != BasisTransform::haar)
    throw Error(where + ": unknown basis transform " + std::to_string(int(field.transform)));
}

void check_lights(const CompressedField& field, const std::string& where) {
  if (field.directions.rows() != field.lights || field.intensities.rows() != field.lights)
    throw Error(where + ": " + std::to_string(field.directions.rows()) + " directions and " +
                std::to_string(field.intensities.rows()) + " intensities, expected " +
                std::to_string(field.lights) + " of each");
  check_finite_rows(field.directions, "direction", where);
  check_finite_rows(field.intensities, "intensity", where);
  for (Eigen::Index i = 0; i < field.directions.rows(); ++i)
    if (!(field.directions.row(i).cast<double>().norm() > 0))
      throw Error(where + ": the direction of light " + std::to_string(i) +
                  " has zero length, expected a direction");
}

void check_mask(const CompressedField& field, const std::string& where) {
  const std::size_t pixels = std::size_t(field.width) * field.height;
  if (field.mask.size() != pixels)
    throw Error(where + ": the mask has " + std::to_string(field.mask.size()) +
                " entries, expected width x height = " + std::to_string(pixels));
}

void check_functions(const CompressedField& field, const std::string& where) {
  const std::uint64_t functions = field.functions();
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t p = field.stored_function[r];
    if (p >= functions)
      throw Error(where + ": " + stored_row_name(r) + " is function " + std::to_string(p) +
                  ", expected < " + std::to_string(functions));
    if (r > 0 && p <= field.stored_function[r - 1])
      throw Error(where + ": " + stored_row_name(r) + " is function " + std::to_string(p) +
                  ", not above the previous row's " + std::to_string(field.stored_function[r - 1]) +
                  " (stored functions must be strictly ascending)");
  }
}

void check_clusters(const CompressedField& field, const std::string& where) {
  if (field.cluster.size() != field.stored_rows())
    throw Error(where + ": " + std::to_string(field.cluster.size()) + " cluster ids for " +
                std::to_string(field.stored_rows()) + " stored rows");
  for (std::size_t r = 0; r < field.cluster.size(); ++r)
    if (field.cluster[r] >= std::uint32_t(field.clusters))
      throw Error(where + ": " + stored_row_name(r) + " has cluster id " +
                  std::to_string(field.cluster[r]) + ", expected < " +
                  std::to_string(field.clusters) + " clusters");
}

void check_bases(const CompressedField& field, const std::string& where) {
  const std::size_t expected = std::size_t(field.clusters) * field.terms * field.lights;
  if (field.bases.size() != expected)
    throw Error(where + ": " + std::to_string(field.bases.size()) +
                " basis values, expected clusters x terms x lights = " + std::to_string(expected));
  for (std::size_t v = 0; v < field.bases.size(); ++v)
    if (!std::isfinite(field.bases[v])) {
      const std::size_t row = v / field.lights;
      throw Error(where + ": basis value of cluster " + std::to_string(row / field.terms) +
                  " term " + std::to_string(row % field.terms) + " light " +
                  std::to_string(v % field.lights) + " is " + std::to_string(field.bases[v]) +
                  ", expected finite");
    }
}

void check_weights(const CompressedField& field, const std::string& where) {
  const auto rows = static_cast<std::size_t>(field.weights.rows());
  if (rows != field.stored_rows() || (rows > 0 && field.weights.cols() != field.terms))
    throw Error(where + ": W is " + std::to_string(rows) + "x" +
                std::to_string(field.weights.cols()) + ", expected stored rows x terms = " +
                std::to_string(field.stored_rows()) + "x" + std::to_string(field.terms));
  // The fast scan first; the loop names the first non-finite weight.
  if (!all_finite(field.weights.data(), std::size_t(field.weights.size())))
    for (std::size_t r = 0; r < rows; ++r)
      for (int j = 0; j < field.terms; ++j)
        if (!std::isfinite(field.weights(Eigen::Index(r), j)))
          throw Error(where + ": weight of " + stored_row_name(r) + " term " + std::to_string(j) +
                      " is " + std::to_string(field.weights(Eigen::Index(r), j)) +
                      ", expected finite");
  const CodedWeights& coded = field.coded_weights;
  if (!coded.empty() && !(std::isfinite(coded.step) && coded.step > 0 &&
                          field.quantization.weight_step == 0 && field.terms > 0))
    throw Error(where + ": W is coded as planes with the step " + std::to_string(coded.step) +
                ", expected a positive step, terms, and no quantization step of its values");
  const std::size_t angles = coded.colour_angles.size();
  if (angles > 0 &&
      (coded.empty() || field.channels != 3 || angles != 3 * std::size_t(field.terms)))
    throw Error(where + ": " + std::to_string(angles) + " colour angles of the weight planes, " +
                "expected none, or 3 per term for planes of a field of three channels");
  for (const std::int16_t angle : coded.colour_angles)
    if (angle == -32768)
      throw Error(where +
                  ": a colour angle of the weight planes is -32768, outside -32767 to 32767");
}

void check_residual_offsets(const CompressedField& field, const std::string& where) {
  const ResidualRows& e = field.residual;
  if (e.light_index.size() != e.values.size())
    throw Error(where + ": " + std::to_string(e.light_index.size()) +
                " residual light indices but " + std::to_string(e.values.size()) +
                " residual values");
  if (field.stored_rows() == 0 && e.row_offsets.size() <= 1 && e.values.empty() &&
      (e.row_offsets.empty() || e.row_offsets[0] == 0))
    return;
  if (e.row_offsets.size() != field.stored_rows() + 1)
    throw Error(where + ": " + std::to_string(e.row_offsets.size()) +
                " residual row offsets, expected stored rows + 1 = " +
                std::to_string(field.stored_rows() + 1));
  if (e.row_offsets.front() != 0)
    throw Error(where + ": the first residual row offset is " +
                std::to_string(e.row_offsets.front()) + ", expected 0");
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    if (e.row_offsets[r + 1] < e.row_offsets[r])
      throw Error(where + ": residual row offsets decrease at " + stored_row_name(r) + " (" +
                  std::to_string(e.row_offsets[r]) + " then " +
                  std::to_string(e.row_offsets[r + 1]) + ")");
  if (e.row_offsets.back() != e.values.size())
    throw Error(where + ": the last residual row offset is " +
                std::to_string(e.row_offsets.back()) + ", expected the " +
                std::to_string(e.values.size()) + " residual entries");
}

void check_residual_indices(const CompressedField& field, const std::string& where) {
  const ResidualRows& e = field.residual;
  // last_row_using[i] = 1 + the last row that used light i, to find duplicates within a row.
  std::vector<std::size_t> last_row_using(field.lights, 0);
  for (std::size_t r = 0; r < e.rows(); ++r)
    for (std::uint32_t k = e.row_offsets[r]; k < e.row_offsets[r + 1]; ++k) {
      const std::uint32_t light = e.light_index[k];
      if (light >= std::uint32_t(field.lights))
        throw Error(where + ": residual entry " + std::to_string(k - e.row_offsets[r]) + " of " +
                    stored_row_name(r) + " is at light " + std::to_string(light) + ", expected < " +
                    std::to_string(field.lights) + " lights");
      if (last_row_using[light] == r + 1)
        throw Error(where + ": " + stored_row_name(r) + " has two residual entries at light " +
                    std::to_string(light));
      last_row_using[light] = r + 1;
    }
}

void check_residual_values(const CompressedField& field, const std::string& where) {
  const ResidualRows& e = field.residual;
  for (std::size_t r = 0; r < e.rows(); ++r)
    for (std::uint32_t k = e.row_offsets[r]; k < e.row_offsets[r + 1]; ++k) {
      const float v = e.values[k];
      if (!std::isfinite(v))
        throw Error(where + ": residual entry " + std::to_string(k - e.row_offsets[r]) + " of " +
                    stored_row_name(r) + " is " + std::to_string(v) + ", expected finite");
      if (k > e.row_offsets[r] && std::abs(v) > std::abs(e.values[k - 1]))
        throw Error(where + ": residual entries of " + stored_row_name(r) +
                    " are not sorted by |value| descending (entry " +
                    std::to_string(k - e.row_offsets[r]) + " is " + std::to_string(v) + " after " +
                    std::to_string(e.values[k - 1]) + ")");
    }
}

void check_dark_pixels(const CompressedField& field, const std::string& where) {
  const std::uint64_t pixels = std::uint64_t(field.width) * field.height;
  std::size_t row = 0;
  for (std::size_t d = 0; d < field.dark_pixels.size(); ++d) {
    const std::uint32_t q = field.dark_pixels[d];
    if (q >= pixels || (d > 0 && q <= field.dark_pixels[d - 1]))
      throw Error(where + ": dark pixel " + std::to_string(d) + " is pixel " + std::to_string(q) +
                  ", expected strictly ascending pixels below " + std::to_string(pixels));
    if (!field.mask[q])
      throw Error(where + ": dark pixel " + std::to_string(q) + " lies outside the mask");
    while (row < field.stored_rows() && field.stored_function[row] / field.channels < q) ++row;
    if (row < field.stored_rows() && field.stored_function[row] / field.channels == q)
      throw Error(where + ": dark pixel " + std::to_string(q) + " also has " +
                  stored_row_name(row) + ", expected a pixel to be stored or dark, not both");
  }
}

void check_dark_values(const CompressedField& field, const std::string& where) {
  const std::size_t expected =
      field.dark_pixels.empty() ? 0 : std::size_t(field.channels) * field.lights;
  if (field.dark.size() != expected)
    throw Error(where + ": " + std::to_string(field.dark.size()) + " dark values, expected " +
                std::to_string(expected) + " (channels x lights when any pixel is dark)");
  for (std::size_t v = 0; v < field.dark.size(); ++v)
    if (!std::isfinite(field.dark[v]))
      throw Error(where + ": the dark value of channel " + std::to_string(v / field.lights) +
                  " light " + std::to_string(v % field.lights) + " is " +
                  std::to_string(field.dark[v]) + ", expected finite");
}

void check_dark_gains(const CompressedField& field, const std::string& where) {
  if (field.dark_gains.empty()) return;
  const std::size_t expected = field.dark_pixels.size() * std::size_t(field.channels);
  if (field.dark_gains.size() != expected)
    throw Error(where + ": " + std::to_string(field.dark_gains.size()) + " dark gains, expected " +
                std::to_string(expected) + " (dark pixels x channels, or none)");
  if (!std::isfinite(field.dark_gain_step) || !(field.dark_gain_step > 0))
    throw Error(where + ": the dark gain step is " + std::to_string(field.dark_gain_step) +
                ", expected a finite value > 0");
  for (std::size_t v = 0; v < field.dark_gains.size(); ++v)
    if (!std::isfinite(field.dark_gains[v]) || field.dark_gains[v] < 0)
      throw Error(where + ": the dark gain of pixel " +
                  std::to_string(field.dark_pixels[v / field.channels]) + " channel " +
                  std::to_string(v % field.channels) + " is " +
                  std::to_string(field.dark_gains[v]) + ", expected finite and >= 0");
}

void validate_compressed_field(const CompressedField& field, const std::string& context) {
  check_dimensions(field, context);
  check_lights(field, context);
  check_mask(field, context);
  check_functions(field, context);
  check_clusters(field, context);
  check_bases(field, context);
  check_weights(field, context);
  check_residual_offsets(field, context);
  check_residual_indices(field, context);
  check_residual_values(field, context);
  check_dark_pixels(field, context);
  check_dark_values(field, context);
  check_dark_gains(field, context);
}

}  // namespace relume
