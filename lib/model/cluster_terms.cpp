// Implementation of the choice of terms per cluster.
#include "model/cluster_terms.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <numeric>
#include <queue>

#include "core/parallel.hpp"
#include "model/haar_transform.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

using MatrixD = Eigen::MatrixXd;

// Bytes one basis row of a cluster costs as stored by default: a 16-bit weight per row of the
// cluster and one 8-bit basis value per light. Only the ratio between clusters matters.
double term_bytes(std::size_t cluster_rows, int lights) {
  return 2.0 * double(cluster_rows) + double(lights);
}

// Every stored row's energy ||R[p,:]||^2 in the original field (the Haar transform keeps it).
std::vector<double> row_energies(const ReflectanceField& original, const CompressedField& field,
                                 unsigned threads) {
  std::vector<double> energy(field.stored_rows());
  parallel_for(energy.size(), threads, [&](std::size_t r, unsigned) {
    energy[r] =
        original.values.row(Eigen::Index(field.stored_function[r])).cast<double>().squaredNorm();
  });
  return energy;
}

// Cluster k's used basis rows made orthonormal and ordered by the Eq. 16 energy of their weights
// (largest first), written into its first slots; the other slots and their weights become zero.
// W F^k of every row of the cluster is unchanged up to rounding.
void orthonormalise_cluster(CompressedField& field, int k, const std::vector<std::size_t>& rows,
                            const std::vector<double>& energy,
                            const std::vector<std::uint8_t>& used) {
  const int t = field.terms, m = field.lights;
  std::vector<int> active;
  for (int j = 0; j < t; ++j)
    if (used[std::size_t(k) * t + j]) active.push_back(j);
  const int a = int(active.size());
  if (a == 0) return;
  float* f = field.bases.data() + std::size_t(k) * t * m;
  MatrixD basis(a, m);
  for (int q = 0; q < a; ++q)
    for (int i = 0; i < m; ++i) basis(q, i) = f[std::size_t(active[q]) * m + i];
  const Eigen::JacobiSVD<MatrixD> svd(basis, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const MatrixD to_orthonormal = svd.matrixU() * svd.singularValues().asDiagonal();  // a x a
  const MatrixD rows_v = svd.matrixV().transpose();                                  // a x m

  // Weights in the orthonormal rows, and their Gram matrix weighted as Eq. 16 weighs each row.
  MatrixD weights(Eigen::Index(rows.size()), a);
  MatrixD gram = MatrixD::Zero(a, a);
  for (std::size_t s = 0; s < rows.size(); ++s) {
    Eigen::RowVectorXd w(a);
    for (int q = 0; q < a; ++q) w(q) = field.weights(Eigen::Index(rows[s]), active[q]);
    weights.row(Eigen::Index(s)) = w * to_orthonormal;
    if (energy[rows[s]] > 0)
      gram.noalias() +=
          weights.row(Eigen::Index(s)).transpose() * weights.row(Eigen::Index(s)) / energy[rows[s]];
  }
  // Eigenvectors in ascending order of eigenvalue: reversed, the strongest direction first.
  const Eigen::SelfAdjointEigenSolver<MatrixD> eigen(gram);
  const MatrixD order = eigen.eigenvectors().rowwise().reverse();
  const MatrixD new_rows = order.transpose() * rows_v;
  const MatrixD new_weights = weights * order;

  std::fill(f, f + std::size_t(t) * m, 0.0f);
  for (int q = 0; q < a; ++q)
    for (int i = 0; i < m; ++i) f[std::size_t(q) * m + i] = float(new_rows(q, i));
  for (std::size_t s = 0; s < rows.size(); ++s) {
    auto w = field.weights.row(Eigen::Index(rows[s]));
    w.setZero();
    for (int q = 0; q < a; ++q) w(q) = float(new_weights(Eigen::Index(s), q));
  }
}

// What zeroing basis row j of each row's cluster adds to the Eq. 16 sum, per (k, j), and the
// Eq. 16 error as it is. With orthonormal rows the additions of several dropped rows add up
// exactly: ||e + sum_j w_j f_j||^2 = ||e||^2 + sum_j (2 w_j <e, f_j> + w_j^2).
struct TermCosts {
  std::vector<double> added;  // clusters x terms, already divided by the functions averaged
  double error = 0;
};

TermCosts measure_term_costs(const ReflectanceField& original, const CompressedField& field,
                             const std::vector<double>& energy, unsigned threads) {
  const int t = field.terms, m = field.lights;
  const unsigned workers = resolve_thread_count(threads);
  struct Sums {
    std::vector<double> added;
    double error = 0;
    std::size_t averaged = 0;
    std::vector<float> exact, approx;
  };
  std::vector<Sums> sums(workers);
  for (Sums& s : sums) {
    s.added.assign(std::size_t(field.clusters) * t, 0.0);
    s.exact.resize(m);
    s.approx.resize(m);
  }
  parallel_for(field.stored_rows(), threads, [&](std::size_t r, unsigned worker) {
    if (!(energy[r] > 0)) return;
    Sums& s = sums[worker];
    const auto original_row = original.values.row(Eigen::Index(field.stored_function[r]));
    std::copy(original_row.data(), original_row.data() + m, s.exact.begin());
    if (field.transform == BasisTransform::haar) haar_forward(s.exact.data(), m, 1);
    reconstruct_stored_row(field, r, all_residual_entries, s.approx.data());
    double squared = 0;
    for (int i = 0; i < m; ++i) {
      s.approx[i] = s.exact[i] - s.approx[i];  // the error e
      squared += double(s.approx[i]) * s.approx[i];
    }
    s.error += squared / energy[r];
    ++s.averaged;
    const int k = int(field.cluster[r]);
    const float* f = field.basis(k);
    for (int j = 0; j < t; ++j) {
      const double w = field.weights(Eigen::Index(r), j);
      if (w == 0) continue;
      double dot = 0;
      for (int i = 0; i < m; ++i) dot += double(s.approx[i]) * f[std::size_t(j) * m + i];
      s.added[std::size_t(k) * t + j] += (2 * w * dot + w * w) / energy[r];
    }
  });
  TermCosts costs;
  costs.added.assign(std::size_t(field.clusters) * t, 0.0);
  std::size_t averaged = 0;
  for (const Sums& s : sums) {
    for (std::size_t i = 0; i < costs.added.size(); ++i) costs.added[i] += s.added[i];
    costs.error += s.error;
    averaged += s.averaged;
  }
  if (averaged > 0) {
    for (double& added : costs.added) added /= double(averaged);
    costs.error /= double(averaged);
  }
  return costs;
}

}  // namespace

std::vector<std::uint8_t> used_basis_rows(const CompressedField& field) {
  std::vector<std::uint8_t> used(std::size_t(field.clusters) * field.terms, 0);
  for (std::size_t row = 0; row < used.size(); ++row) {
    const float* f = field.bases.data() + row * field.lights;
    used[row] = std::any_of(f, f + field.lights, [](float v) { return v != 0; });
  }
  return used;
}

std::vector<int> terms_per_cluster(const CompressedField& field) {
  const std::vector<std::uint8_t> used = used_basis_rows(field);
  std::vector<int> terms(field.clusters, 0);
  for (std::size_t row = 0; row < used.size(); ++row) terms[row / field.terms] += used[row];
  return terms;
}

TermChoice drop_unneeded_terms(const ReflectanceField& original, CompressedField& field,
                               double relative_increase, unsigned threads) {
  TermChoice choice;
  choice.cluster_terms = terms_per_cluster(field);
  const int t = field.terms, K = field.clusters;
  if (!(relative_increase > 0) || t == 0 || t > field.lights) return choice;
  check_original_matches(original, field, all_residual_entries);

  const std::vector<double> energy = row_energies(original, field, threads);
  std::vector<std::vector<std::size_t>> rows_of(K);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) rows_of[field.cluster[r]].push_back(r);
  const std::vector<std::uint8_t> used = used_basis_rows(field);
  parallel_for(std::size_t(K), threads, [&](std::size_t k, unsigned) {
    orthonormalise_cluster(field, int(k), rows_of[k], energy, used);
  });

  const TermCosts costs = measure_term_costs(original, field, energy, threads);
  choice.error_all_terms = costs.error;
  // Each cluster's used rows by the error their removal adds, largest first: drops come off the
  // end, the cheapest first.
  std::vector<std::vector<int>> order(K);
  for (int k = 0; k < K; ++k) {
    for (int j = 0; j < choice.cluster_terms[k]; ++j) order[k].push_back(j);
    std::stable_sort(order[k].begin(), order[k].end(), [&](int a, int b) {
      return costs.added[std::size_t(k) * t + a] > costs.added[std::size_t(k) * t + b];
    });
  }
  // Greedy over the clusters' cheapest remaining rows by added error per byte saved.
  using Candidate = std::pair<double, int>;  // (added error per byte, cluster)
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> cheapest;
  auto offer = [&](int k) {
    if (order[k].empty()) return;
    const double added = costs.added[std::size_t(k) * t + order[k].back()];
    cheapest.push({added / term_bytes(rows_of[k].size(), field.lights), k});
  };
  for (int k = 0; k < K; ++k) offer(k);
  const double allowed = relative_increase * costs.error;
  double spent = 0;
  while (!cheapest.empty()) {
    const int k = cheapest.top().second;
    cheapest.pop();
    const int j = order[k].back();
    const double added = costs.added[std::size_t(k) * t + j];
    if (spent + added > allowed) continue;  // this cluster's next rows cost more still
    spent += added;
    order[k].pop_back();
    ++choice.dropped;
    offer(k);
  }

  // Kept rows move to the front in the order above; dropped rows and their weights become zero.
  for (int k = 0; k < K; ++k) {
    float* f = field.bases.data() + std::size_t(k) * t * field.lights;
    const std::vector<float> before(f, f + std::size_t(t) * field.lights);
    std::fill(f, f + before.size(), 0.0f);
    for (std::size_t q = 0; q < order[k].size(); ++q)
      std::copy_n(before.begin() + std::ptrdiff_t(order[k][q]) * field.lights, field.lights,
                  f + q * field.lights);
    for (std::size_t r : rows_of[k]) {
      auto w = field.weights.row(Eigen::Index(r));
      const Eigen::RowVectorXf old = w;
      w.setZero();
      for (std::size_t q = 0; q < order[k].size(); ++q) w(Eigen::Index(q)) = old(order[k][q]);
    }
    choice.cluster_terms[k] = int(order[k].size());
  }
  choice.error_chosen = costs.error + spent;
  return choice;
}

}  // namespace relume
