// Implementation of clustered PCA (see clustered_pca.hpp). Interruptible between its rounds.
#include "compress/clustered_pca.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <relume/error.hpp>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_basis.hpp"
#include "core/elapsed_time.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

constexpr std::size_t rows_per_task = 512;

// Every cluster as an affine subspace: a mean (zero without centring) and `directions`
// orthonormal components; `components` keeps one more (`terms` in all) for the stored basis.
struct AffineClusters {
  int clusters = 0, terms = 0, directions = 0, lights = 0;
  RowMatrixF means;       // clusters x lights
  RowMatrixF components;  // clusters * terms x lights; row k * terms + j

  const float* component(int k, int j) const {
    return components.data() + (std::size_t(k) * terms + j) * lights;
  }
};

struct AffineAssignment {
  std::vector<std::int32_t> best;
  double squared_error = 0;  // sum over rows of the best cluster's least-squares error
  double l1_error = 0;       // sum over rows of the L1 norm of that residual
};

// Refits the mean and components of every cluster with members (others are kept as they are).
void fit_affine_clusters(const WorkingRows& rows,
                         const std::vector<std::vector<std::uint32_t>>& members, bool centred,
                         unsigned threads, AffineClusters& clusters) {
  parallel_for(std::size_t(clusters.clusters), threads, [&](std::size_t k, unsigned) {
    const auto& list = members[k];
    if (list.empty()) return;
    auto mean = clusters.means.row(static_cast<Eigen::Index>(k));
    mean.setZero();
    if (centred) {
      Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(clusters.lights);
      for (const std::uint32_t r : list) sum += rows.values.row(r).cast<double>();
      mean = (sum / double(list.size())).cast<float>();
    }
    const std::vector<float> basis =
        least_squares_subspace(rows, list, clusters.terms, centred ? mean.data() : nullptr);
    std::copy(basis.begin(), basis.end(),
              clusters.components.data() + k * clusters.terms * clusters.lights);
  });
}

// Every row's cluster with the smallest least-squares error ||x - mu||^2 - ||Q^T (x - mu)||^2
// (Q the cluster's `directions` components), from two products per block of rows.
AffineAssignment nearest_affine_clusters(const WorkingRows& rows, const AffineClusters& clusters,
                                         unsigned threads) {
  const int K = clusters.clusters, r = clusters.directions, lights = clusters.lights;
  // Q_all: the directions of every cluster, (K r) x lights; offsets c_k = Q_k mu_k.
  RowMatrixF q_all(std::size_t(K) * r, lights);
  Eigen::MatrixXf offsets(r, K);
  Eigen::VectorXf mean_energy(K);
  for (int k = 0; k < K; ++k) {
    const auto mean = clusters.means.row(k);
    mean_energy[k] = mean.squaredNorm();
    for (int j = 0; j < r; ++j) {
      const Eigen::Map<const Eigen::RowVectorXf> q(clusters.component(k, j), lights);
      q_all.row(std::size_t(k) * r + j) = q;
      offsets(j, k) = q.dot(mean);
    }
  }
  AffineAssignment result;
  result.best.assign(rows.rows(), 0);
  const std::size_t tasks = (rows.rows() + rows_per_task - 1) / rows_per_task;
  std::vector<double> squared(tasks, 0.0), absolute(tasks, 0.0);
  parallel_for(tasks, threads, [&](std::size_t task, unsigned) {
    const std::size_t begin = task * rows_per_task;
    const std::size_t end = std::min(rows.rows(), begin + rows_per_task);
    const auto block = rows.values.middleRows(begin, end - begin);
    const Eigen::MatrixXf projections = block * q_all.transpose();    // rows x (K r)
    const Eigen::MatrixXf dots = block * clusters.means.transpose();  // rows x K
    Eigen::RowVectorXf residual(lights);
    for (std::size_t row = begin; row < end; ++row) {
      const Eigen::Index b = static_cast<Eigen::Index>(row - begin);
      const float energy = rows.values.row(row).squaredNorm();
      float best_error = HUGE_VALF;
      int best = 0;
      for (int k = 0; k < K; ++k) {
        float error = energy - 2 * dots(b, k) + mean_energy[k];
        for (int j = 0; j < r; ++j) {
          const float p = projections(b, std::size_t(k) * r + j) - offsets(j, k);
          error -= p * p;
        }
        if (error < best_error) {
          best_error = error;
          best = k;
        }
      }
      result.best[row] = best;
      residual = rows.values.row(row) - clusters.means.row(best);
      for (int j = 0; j < r; ++j) {
        const float p = projections(b, std::size_t(best) * r + j) - offsets(j, best);
        residual -= p * q_all.row(std::size_t(best) * r + j);
      }
      squared[task] += residual.squaredNorm();
      absolute[task] += residual.cwiseAbs().sum();
    }
  });
  for (std::size_t task = 0; task < tasks; ++task) {
    result.squared_error += squared[task];
    result.l1_error += absolute[task];
  }
  return result;
}

// Cluster k's stored basis: an orthonormal basis of the span of its mean and its first terms - 1
// components (the mean orthogonalised against them; when the mean lies in their span, the next
// component instead), or its terms components without centring.
void stored_basis(const AffineClusters& clusters, int k, bool centred, float* basis) {
  const int terms = clusters.terms, lights = clusters.lights;
  std::copy(clusters.component(k, 0), clusters.component(k, 0) + std::size_t(terms) * lights,
            basis);
  if (!centred) return;
  Eigen::VectorXd mean = clusters.means.row(k).transpose().cast<double>();
  const double length = mean.norm();
  for (int pass = 0; pass < 2; ++pass) {  // Gram-Schmidt, twice for stability
    for (int j = 0; j < terms - 1; ++j) {
      const Eigen::Map<const Eigen::VectorXf> q(clusters.component(k, j), lights);
      mean -= q.cast<double>().dot(mean) * q.cast<double>();
    }
  }
  if (mean.norm() > 1e-6 * length && mean.norm() > 0) {
    const Eigen::VectorXf unit = (mean / mean.norm()).cast<float>();
    std::copy(unit.data(), unit.data() + lights, basis + std::size_t(terms - 1) * lights);
  }
}

// The least-squares weights of every row in its cluster's (orthonormal) basis.
RowMatrixF projection_weights(const WorkingRows& rows, const ClusterModel& model,
                              unsigned threads) {
  RowMatrixF weights(static_cast<Eigen::Index>(rows.rows()), model.terms);
  parallel_for(rows.rows(), threads, [&](std::size_t r, unsigned) {
    const Eigen::Map<const RowMatrixF> basis(model.basis(model.assignment[r]), model.terms,
                                             model.lights);
    weights.row(static_cast<Eigen::Index>(r)) = rows.values.row(r) * basis.transpose();
  });
  return weights;
}

}  // namespace

PcaCentering parse_pca_centering(const std::string& text) {
  if (text == "mean") return PcaCentering::mean;
  if (text == "none") return PcaCentering::none;
  throw Error("PCA centring must be 'mean' or 'none', got '" + text + "'");
}

std::string to_string(PcaCentering centering) {
  return centering == PcaCentering::mean ? "mean" : "none";
}

ClusterModel cluster_rows_pca(const WorkingRows& rows, const ClusteringOptions& clustering,
                              const ClusteredPcaOptions& options, ClusteringTrace& trace) {
  if (options.iterations < 0)
    throw Error("clustered PCA iterations must be >= 0, got " + std::to_string(options.iterations));
  const bool centred = options.centering == PcaCentering::mean;
  ClusterModel model = seed_clusters_for(rows, clustering, trace);
  auto start = Clock::now();

  AffineClusters clusters;
  clusters.clusters = model.clusters;
  clusters.terms = model.terms;
  clusters.directions = centred ? model.terms - 1 : model.terms;
  clusters.lights = model.lights;
  clusters.means.setZero(model.clusters, model.lights);
  clusters.components = Eigen::Map<const RowMatrixF>(
      model.bases.data(), std::size_t(model.clusters) * model.terms, model.lights);

  ProgressReporter progress("compress: clustered PCA", std::uint64_t(options.iterations) + 1,
                            clustering.quiet);
  trace.settled = false;
  for (int iteration = 0; iteration <= options.iterations; ++iteration) {
    const auto round_start = Clock::now();
    // The seeding's subspaces are already the least-squares fit of its assignment without
    // centring; with centring the first round fits means and components to it.
    if (iteration > 0 || centred) {
      start = Clock::now();
      fit_affine_clusters(rows, model.members(), centred, clustering.threads, clusters);
      trace.basis_seconds += seconds_since(start);
    }
    start = Clock::now();
    AffineAssignment assigned = nearest_affine_clusters(rows, clusters, clustering.threads);
    trace.assignment_seconds += seconds_since(start);
    IterationRecord record;
    record.iteration = iteration;
    record.objective = assigned.l1_error;
    record.clusters = model.clusters;
    for (std::size_t r = 0; r < rows.rows(); ++r)
      record.changed += assigned.best[r] != model.assignment[r];
    model.assignment = std::move(assigned.best);
    record.seconds = seconds_since(round_start);
    trace.iterations.push_back(record);
    progress.advance();
    if (iteration > 0 &&
        double(record.changed) <= clustering.settle_fraction * double(rows.rows())) {
      trace.settled = true;
      break;
    }
  }
  progress.finish();

  // The stored model: orthonormal bases of the spans, each row in the cluster whose span fits it
  // best and its least-squares weights there, then the L1 method's cluster size rules with
  // least-squares fits (IRLS without reweighting) for the rows they move.
  start = Clock::now();
  for (int k = 0; k < model.clusters; ++k) stored_basis(clusters, k, centred, model.basis(k));
  CandidateOptions nearest;
  nearest.count = 1;
  const CandidateLists best = nearest_subspace_candidates(rows, model, nearest, clustering.threads);
  model.assignment.assign(best.clusters.begin(), best.clusters.end());
  model.weights = projection_weights(rows, model, clustering.threads);
  trace.candidate_seconds += seconds_since(start);
  start = Clock::now();
  IrlsSettings least_squares;
  least_squares.iterations = 0;
  if (!trace.iterations.empty())
    trace.iterations.back().size_rules =
        enforce_cluster_sizes(rows, model, clustering.sizes, 1, least_squares, clustering.threads);
  trace.size_rule_seconds += seconds_since(start);
  if (!trace.iterations.empty()) trace.iterations.back().clusters = model.clusters;
  return model;
}

}  // namespace relume
