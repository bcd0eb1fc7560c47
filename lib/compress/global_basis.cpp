// Implementation of the one-basis model (see global_basis.hpp).
#include "compress/global_basis.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <vector>

#include "compress/leading_subspace.hpp"
#include "core/parallel.hpp"
#include "core/value_scans.hpp"

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

// The 12-bit step of `row`'s largest value: the finest a term is stored at.
double finest_step(const Eigen::RowVectorXd& row) {
  return std::max(row.cwiseAbs().maxCoeff(), 1e-30) / (std::ldexp(1.0, global_basis_bits - 1) - 1);
}

// Steps for `basis` (terms x lights). A basis error d in term j costs |W[:,j]|^2 |d|^2 in the
// light images (term_energy[j] = |W[:,j]|^2). The steps are allotted so each term's share is
// equal (reverse water-filling: step_j ~ 1 / |W[:,j]|) and all of them together add
// `added_error` (a sum over every stored value); never finer than finest_step (the whole basis,
// where nothing is truncated), never coarser than 4x the largest value (every integer 0, as for
// a term no weight uses).
std::vector<double> basis_steps(const Eigen::MatrixXd& basis, const Eigen::VectorXd& term_energy,
                                double added_error) {
  const Eigen::Index terms = basis.rows(), lights = basis.cols();
  std::vector<double> steps;
  for (Eigen::Index j = 0; j < terms; ++j) {
    const double finest = finest_step(basis.row(j)),
                 coarsest = 4 * basis.row(j).cwiseAbs().maxCoeff();
    steps.push_back(
        term_energy[j] > 0
            ? std::clamp(std::sqrt(12 * added_error / double(terms * lights * term_energy[j])),
                         finest, std::max(coarsest, finest))
            : std::max(coarsest, finest));
  }
  return steps;
}

// `basis` as out.bases: integers of at most global_basis_bits bits times steps[j] in term j.
void store_quantized_basis(const Eigen::MatrixXd& basis, const std::vector<double>& steps,
                           CompressedField& out) {
  ValueQuantization& quantization = out.quantization;
  quantization.basis_bits = global_basis_bits;
  quantization.basis_scales.clear();
  out.bases.resize(std::size_t(basis.size()));
  for (Eigen::Index j = 0; j < basis.rows(); ++j) {
    const float scale = float(steps[std::size_t(j)]);
    quantization.basis_scales.push_back(scale);
    for (Eigen::Index i = 0; i < basis.cols(); ++i)
      out.bases[std::size_t(j * basis.cols() + i)] = float(std::round(basis(j, i) / scale) * scale);
  }
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
                                   int terms, unsigned threads,
                                   const std::vector<float>& noise_sigma) {
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
  out.non_negative = all_non_negative(field.values.data(), std::size_t(field.values.size()));

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
  const double truncation = std::max(0.0, field_energy - term_energy.sum());
  double noise_energy = 0;
  for (const std::uint32_t function : out.stored_function)
    if (const std::size_t channel = function % std::uint32_t(field.channels);
        channel < noise_sigma.size())
      noise_energy += double(field.lights()) * double(noise_sigma[channel]) * noise_sigma[channel];
  const Eigen::MatrixXd basis = directions.topRows(terms);
  store_quantized_basis(
      basis,
      basis_steps(basis, term_energy, basis_error_share * std::max(truncation, noise_energy)), out);
  out.residual.row_offsets.assign(out.stored_function.size() + 1, 0);
  return out;
}

void refit_global_basis(const ReflectanceField& field, CompressedField& coded, unsigned threads) {
  const int terms = coded.terms, lights = coded.lights;
  const std::size_t rows = coded.stored_function.size();
  if (coded.clusters != 1 || field.lights() != lights || std::size_t(coded.weights.rows()) != rows)
    throw Error("refit_global_basis: a one-basis field of " + std::to_string(lights) +
                " lights and its stored rows expected");
  // W^T W and W^T X over the stored rows X, summed in a fixed number of chunks (each in
  // row order, then the chunks in order): the same sums for any thread count.
  constexpr std::size_t chunks = 64, block = 1024;
  std::vector<Eigen::MatrixXd> gram(chunks, Eigen::MatrixXd::Zero(terms, terms));
  std::vector<Eigen::MatrixXd> cross(chunks, Eigen::MatrixXd::Zero(terms, lights));
  parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
    const std::size_t end = rows * (c + 1) / chunks;
    RowMatrixF values(Eigen::Index(block), lights);
    for (std::size_t first = rows * c / chunks; first < end; first += block) {
      const auto count = Eigen::Index(std::min(block, end - first));
      for (Eigen::Index r = 0; r < count; ++r)
        values.row(r) = field.values.row(coded.stored_function[first + std::size_t(r)]);
      const auto weights = coded.weights.middleRows(Eigen::Index(first), count);
      gram[c] += (weights.transpose() * weights).cast<double>();
      cross[c] += (weights.transpose() * values.topRows(count)).cast<double>();
    }
  });
  Eigen::MatrixXd weight_gram = Eigen::MatrixXd::Zero(terms, terms);
  Eigen::MatrixXd weight_cross = Eigen::MatrixXd::Zero(terms, lights);
  for (std::size_t c = 0; c < chunks; ++c) {
    weight_gram += gram[c];
    weight_cross += cross[c];
  }
  // F = (W^T W)^-1 W^T X. A term whose weights decode to (nearly) nothing is left undetermined by
  // the fit: a ridge towards the basis the weights were coded for keeps it.
  Eigen::MatrixXd coded_for(terms, lights);
  for (int j = 0; j < terms; ++j)
    for (int i = 0; i < lights; ++i) coded_for(j, i) = coded.bases[std::size_t(j) * lights + i];
  const double ridge = 1e-12 * std::max(weight_gram.trace() / terms, 1e-300);
  const Eigen::MatrixXd refit = (weight_gram + ridge * Eigen::MatrixXd::Identity(terms, terms))
                                    .ldlt()
                                    .solve(weight_cross + ridge * coded_for);
  // The steps the weights were coded for, so that the basis costs about the bytes it was
  // planned at; finer never, coarser only where a row outgrew its 12 bits.
  std::vector<double> steps;
  for (int j = 0; j < terms; ++j)
    steps.push_back(std::max(double(coded.quantization.basis_scales[std::size_t(j)]),
                             finest_step(refit.row(j))));
  store_quantized_basis(refit, steps, coded);
}

}  // namespace relume
