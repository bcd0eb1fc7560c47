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

double fit_cluster_basis_l1(const WorkingRows& rows, const std::vector<std::uint32_t>& members,
                            const RowMatrixF& weights, const IrlsSettings& settings, int terms,
                            float* basis) {
  const int lights = rows.lights();
  const int pairs = terms * (terms + 1) / 2;
  // Accumulators per light: the weighted Gram (pairs j >= l) and right-hand side (terms).
  std::vector<double> gram(std::size_t(pairs) * lights), rhs(std::size_t(terms) * lights);
  std::vector<double> objective(lights), best_objective(lights, HUGE_VAL);
  std::vector<float> best(std::size_t(terms) * lights), residual(lights);
  std::vector<double> inverse(lights);
  const float epsilon = settings.epsilon;  // rows have unit norm

  for (int iteration = 0; iteration <= settings.iterations; ++iteration) {
    const bool solve = iteration < settings.iterations;
    std::fill(objective.begin(), objective.end(), 0.0);
    if (solve) {
      std::fill(gram.begin(), gram.end(), 0.0);
      std::fill(rhs.begin(), rhs.end(), 0.0);
    }
    for (const std::uint32_t p : members) {
      const float* x = rows.row(p);
      const float* w = weights.row(p).data();
      std::copy(x, x + lights, residual.begin());
      for (int j = 0; j < terms; ++j) {
        const float* f = basis + std::size_t(j) * lights;
        for (int i = 0; i < lights; ++i) residual[i] -= w[j] * f[i];
      }
      for (int i = 0; i < lights; ++i) {
        const double magnitude = std::fabs(residual[i]);
        objective[i] += magnitude;
        inverse[i] = 1.0 / std::max<double>(magnitude, epsilon);
      }
      if (!solve) continue;
      int pair = 0;
      for (int j = 0; j < terms; ++j) {
        for (int l = 0; l <= j; ++l, ++pair) {
          const double product = double(w[j]) * w[l];
          double* g = gram.data() + std::size_t(pair) * lights;
          for (int i = 0; i < lights; ++i) g[i] += inverse[i] * product;
        }
        double* b = rhs.data() + std::size_t(j) * lights;
        const double wj = w[j];
        for (int i = 0; i < lights; ++i) b[i] += inverse[i] * wj * x[i];
      }
    }
    for (int i = 0; i < lights; ++i) {
      if (objective[i] < best_objective[i]) {
        best_objective[i] = objective[i];
        for (int j = 0; j < terms; ++j)
          best[std::size_t(j) * lights + i] = basis[std::size_t(j) * lights + i];
      }
    }
    if (!solve) break;
    for (int i = 0; i < lights; ++i) {
      double g[max_cluster_terms * max_cluster_terms], b[max_cluster_terms];
      int pair = 0;
      for (int j = 0; j < terms; ++j) {
        for (int l = 0; l <= j; ++l, ++pair)
          g[j * terms + l] = g[l * terms + j] = gram[std::size_t(pair) * lights + i];
        b[j] = rhs[std::size_t(j) * lights + i];
      }
      solve_small_spd(g, b, terms);
      for (int j = 0; j < terms; ++j) basis[std::size_t(j) * lights + i] = static_cast<float>(b[j]);
    }
  }
  std::copy(best.begin(), best.end(), basis);
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
  for (const double value : best_objective) total += value;
  return total;
}

}  // namespace relume
