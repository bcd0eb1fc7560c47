// Implementation of cluster basis fitting (see cluster_basis.hpp).
#include "compress/cluster_basis.hpp"

#include <algorithm>
#include <cmath>

#include "compress/leading_subspace.hpp"

namespace relume {

std::vector<float> least_squares_subspace(const WorkingRows& rows,
                                          const std::vector<std::uint32_t>& members, int terms,
                                          const float* center, const float* warm_start) {
  const int lights = rows.lights();
  RowMatrixF gathered(static_cast<Eigen::Index>(members.size()), lights);
  for (std::size_t k = 0; k < members.size(); ++k)
    gathered.row(static_cast<Eigen::Index>(k)) = rows.values.row(members[k]);
  if (center) gathered.rowwise() -= Eigen::Map<const Eigen::RowVectorXf>(center, lights);
  const Eigen::MatrixXd subspace =
      leading_right_singular_vectors(gathered, terms, SubspaceMethod::automatic, warm_start);
  std::vector<float> basis(std::size_t(terms) * lights);
  for (int j = 0; j < terms; ++j)
    for (int i = 0; i < lights; ++i)
      basis[std::size_t(j) * lights + i] = static_cast<float>(subspace(j, i));
  return basis;
}

Eigen::MatrixXf orthonormal_columns(const float* basis, int terms, int lights) {
  Eigen::MatrixXd q = Eigen::Map<const RowMatrixF>(basis, terms, lights).transpose().cast<double>();
  orthonormalise_columns(q, DependentColumn::zero);
  return q.cast<float>();
}

BasisIrlsFit::BasisIrlsFit(int terms, int lights, float epsilon)
    : terms_(terms),
      lights_(lights),
      epsilon_(epsilon),
      rhs_offset_(std::size_t(terms) * (terms + 1) / 2 * lights),
      objective_offset_(rhs_offset_ + std::size_t(terms) * lights),
      sums_(objective_offset_ + std::size_t(lights)),
      best_objective_(lights, HUGE_VAL),
      best_(std::size_t(terms) * lights),
      residual_(lights),
      inverse_(lights) {}

void BasisIrlsFit::start_round() { std::fill(sums_.begin(), sums_.end(), 0.0); }

void BasisIrlsFit::add(const float* x, const float* w, const float* basis, bool objective_only) {
  const int terms = terms_, lights = lights_;
  std::copy(x, x + lights, residual_.begin());
  for (int j = 0; j < terms; ++j) {
    const float* f = basis + std::size_t(j) * lights;
    for (int i = 0; i < lights; ++i) residual_[i] -= w[j] * f[i];
  }
  double* objective = sums_.data() + objective_offset_;
  for (int i = 0; i < lights; ++i) {
    const double magnitude = std::fabs(residual_[i]);
    objective[i] += magnitude;
    inverse_[i] = 1.0 / std::max<double>(magnitude, epsilon_);
  }
  if (objective_only) return;
  int pair = 0;
  for (int j = 0; j < terms; ++j) {
    for (int l = 0; l <= j; ++l, ++pair) {
      const double product = double(w[j]) * w[l];
      double* g = sums_.data() + std::size_t(pair) * lights;
      for (int i = 0; i < lights; ++i) g[i] += inverse_[i] * product;
    }
    double* b = sums_.data() + rhs_offset_ + std::size_t(j) * lights;
    const double wj = w[j];
    for (int i = 0; i < lights; ++i) b[i] += inverse_[i] * wj * x[i];
  }
}

void BasisIrlsFit::end_round(float* basis, bool solve) {
  const int terms = terms_, lights = lights_;
  const double* objective = sums_.data() + objective_offset_;
  for (int i = 0; i < lights; ++i) {
    if (objective[i] < best_objective_[i]) {
      best_objective_[i] = objective[i];
      for (int j = 0; j < terms; ++j)
        best_[std::size_t(j) * lights + i] = basis[std::size_t(j) * lights + i];
    }
  }
  if (!solve) return;
  for (int i = 0; i < lights; ++i) {
    double g[max_cluster_terms * max_cluster_terms], b[max_cluster_terms];
    int pair = 0;
    for (int j = 0; j < terms; ++j) {
      for (int l = 0; l <= j; ++l, ++pair)
        g[j * terms + l] = g[l * terms + j] = sums_[std::size_t(pair) * lights + i];
      b[j] = sums_[rhs_offset_ + std::size_t(j) * lights + i];
    }
    solve_small_spd(g, b, terms);
    for (int j = 0; j < terms; ++j) basis[std::size_t(j) * lights + i] = static_cast<float>(b[j]);
  }
}

double BasisIrlsFit::finish(float* basis) const {
  const int terms = terms_, lights = lights_;
  std::copy(best_.begin(), best_.end(), basis);
  for (int j = 0; j < terms; ++j) {
    float* f = basis + std::size_t(j) * lights;
    double norm = 0;
    for (int i = 0; i < lights; ++i) norm += double(f[i]) * f[i];
    if (norm > 0) {
      const float scale = static_cast<float>(1.0 / std::sqrt(norm));
      for (int i = 0; i < lights; ++i) f[i] *= scale;
    }
  }
  double total = 0;
  for (const double value : best_objective_) total += value;
  return total;
}

double fit_cluster_basis_l1(const WorkingRows& rows, const std::vector<std::uint32_t>& members,
                            const RowMatrixF& weights, const IrlsSettings& settings, int terms,
                            float* basis) {
  BasisIrlsFit fit(terms, rows.lights(), settings.epsilon);  // rows have unit norm
  for (int round = 0; round <= settings.iterations; ++round) {
    const bool solve = round < settings.iterations;
    fit.start_round();
    for (const std::uint32_t p : members)
      fit.add(rows.row(p), weights.row(p).data(), basis, !solve);
    fit.end_round(basis, solve);
  }
  return fit.finish(basis);
}

}  // namespace relume
