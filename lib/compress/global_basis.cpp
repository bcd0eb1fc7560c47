// Implementation of the one-basis model (see global_basis.hpp).
#include "compress/global_basis.hpp"

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <vector>

#include "compress/leading_subspace.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace {

// The functions inside the mask with non-zero energy, ascending.
std::vector<std::uint32_t> stored_functions(const ReflectanceField& field) {
  std::vector<std::uint32_t> stored;
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    const std::size_t pixel = std::size_t(p / field.channels);
    if (!field.mask.empty() && !field.mask[pixel]) continue;
    if (field.values.row(p).squaredNorm() > 0) stored.push_back(std::uint32_t(p));
  }
  return stored;
}

}  // namespace

Eigen::MatrixXd global_basis_directions(const ReflectanceField& field, int terms) {
  if (terms < 1 || terms > field.lights())
    throw Error("a global basis of " + std::to_string(terms) + " terms for " +
                std::to_string(field.lights()) + " lights: expected 1 to the light count");
  if (field.functions() >= (std::int64_t(1) << 32))
    throw Error("a global basis needs fewer than 2^32 functions, the field has " +
                std::to_string(field.functions()));
  bool all_inside = true;
  for (const std::uint8_t inside : field.mask) all_inside = all_inside && inside;
  // Outside the mask nothing is stored: those functions do not shape the basis. Zero functions
  // add nothing to X^T X, so the whole field serves when every pixel is inside.
  if (all_inside) return leading_right_singular_vectors(field.values, terms);
  const std::vector<std::uint32_t> stored = stored_functions(field);
  RowMatrixF inside(Eigen::Index(stored.size()), field.lights());
  for (std::size_t r = 0; r < stored.size(); ++r)
    inside.row(Eigen::Index(r)) = field.values.row(stored[r]);
  return leading_right_singular_vectors(inside, terms);
}

CompressedField global_basis_field(const ReflectanceField& field, const Eigen::MatrixXd& directions,
                                   int terms, unsigned threads) {
  if (terms < 1 || terms > directions.rows() || directions.cols() != field.lights())
    throw Error("a global basis of " + std::to_string(terms) + " terms from " +
                std::to_string(directions.rows()) + " directions of " +
                std::to_string(directions.cols()) + " lights, for a field of " +
                std::to_string(field.lights()) + " lights");
  CompressedField out;
  out.width = field.width;
  out.height = field.height;
  out.channels = field.channels;
  out.lights = field.lights();
  out.terms = terms;
  out.clusters = 1;
  out.mask =
      field.mask.empty() ? std::vector<std::uint8_t>(std::size_t(field.pixels()), 1) : field.mask;
  out.directions = field.directions;
  out.intensities = field.intensities;
  out.non_negative = (field.values.array() >= 0.0f).all();

  // Each function's projection on the unquantized basis: the rank-`terms` fit.
  out.stored_function = stored_functions(field);
  out.cluster.assign(out.stored_function.size(), 0);
  out.weights.resize(Eigen::Index(out.stored_function.size()), terms);
  // Blocks of rows gathered and multiplied at once, the blocks spread over the threads.
  const Eigen::MatrixXf exact_t = directions.topRows(terms).transpose().cast<float>();
  constexpr std::size_t block = 1024;
  const std::size_t stored = out.stored_function.size();
  // Each block's energy, and each term's energy in its weights, summed in block order.
  const std::size_t blocks = (stored + block - 1) / block;
  std::vector<double> block_energy(blocks, 0.0);
  std::vector<Eigen::VectorXd> block_term_energy(blocks, Eigen::VectorXd::Zero(terms));
  parallel_for(blocks, threads, [&](std::size_t b, unsigned) {
    const std::size_t first = b * block, count = std::min(block, stored - first);
    RowMatrixF values(Eigen::Index(count), field.lights());
    for (std::size_t r = 0; r < count; ++r) {
      values.row(Eigen::Index(r)) = field.values.row(out.stored_function[first + r]);
      block_energy[b] += double(values.row(Eigen::Index(r)).squaredNorm());
    }
    auto weights = out.weights.middleRows(Eigen::Index(first), Eigen::Index(count));
    weights.noalias() = values * exact_t;
    for (std::size_t r = 0; r < count; ++r)
      block_term_energy[b] += weights.row(Eigen::Index(r)).cast<double>().cwiseAbs2().transpose();
  });
  double field_energy = 0;
  Eigen::VectorXd term_energy = Eigen::VectorXd::Zero(terms);
  for (std::size_t b = 0; b < blocks; ++b) {
    field_energy += block_energy[b];
    term_energy += block_term_energy[b];
  }
  // A basis error d in term j costs |W[:,j]|^2 |d|^2 in the light images. The steps are
  // allotted so each term's share is equal (reverse water-filling: step_j ~ 1 / |W[:,j]|) and
  // all of them together add `basis_error_share` to the error of truncating at `terms`; never
  // finer than 12 bits of the term's largest value (the whole basis, or a flat field).
  const double rows = double(std::max<std::size_t>(out.stored_function.size(), 1));
  const double truncation = std::max(0.0, field_energy - term_energy.sum()) / (rows * out.lights);
  const double basis_error = basis_error_share * truncation;  // per light-image value
  ValueQuantization& quantization = out.quantization;
  quantization.basis_bits = global_basis_bits;
  const double largest_integer = std::ldexp(1.0, global_basis_bits - 1) - 1;
  out.bases.resize(std::size_t(terms) * std::size_t(out.lights));
  for (int j = 0; j < terms; ++j) {
    const double largest = std::max(directions.row(j).cwiseAbs().maxCoeff(), 1e-30);
    double step = largest / largest_integer;
    if (term_energy[j] > 0)  // at most 4x the largest value: every integer is 0 by then
      step = std::clamp(std::sqrt(12 * rows * basis_error / (terms * term_energy[j])), step,
                        4 * largest);
    const float scale = float(step);
    quantization.basis_scales.push_back(scale);
    for (int i = 0; i < out.lights; ++i)
      out.bases[std::size_t(j) * out.lights + i] =
          float(std::round(directions(j, i) / scale) * scale);
  }
  out.residual.row_offsets.assign(out.stored_function.size() + 1, 0);
  return out;
}

}  // namespace relume
