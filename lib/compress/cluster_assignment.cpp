// Implementation of candidate preselection and the CPU assignment (see cluster_assignment.hpp).
#include "compress/cluster_assignment.hpp"

#include <algorithm>
#include <utility>

#include "compress/cluster_basis.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

constexpr std::size_t rows_per_task = 512;

std::size_t task_count(std::size_t rows, std::size_t per_task = rows_per_task) {
  return (rows + per_task - 1) / per_task;
}

// The projections of a task's rows on every basis vector are held at once: at 100,000 clusters of
// 2 terms, 512 rows of them took 400 MB per thread. A task takes fewer rows then.
constexpr std::uint64_t projection_block_bytes = std::uint64_t(8) << 20;

std::size_t projected_rows_per_task(std::uint64_t basis_vectors) {
  const std::uint64_t fitting = projection_block_bytes / sizeof(float) / std::max<std::uint64_t>(1, basis_vectors);
  return std::size_t(std::clamp<std::uint64_t>(fitting, 1, rows_per_task));
}

// Keeps the `count` smallest (error, cluster) pairs best first, making sure `include` is among
// them, and writes them to `out` (padding with -1).
void write_best(std::vector<std::pair<float, std::int32_t>>& scored, int count,
                std::int32_t include, std::int32_t* out) {
  const std::size_t kept = std::min<std::size_t>(scored.size(), std::size_t(count));
  std::partial_sort(scored.begin(), scored.begin() + kept, scored.end());
  bool included = include < 0;
  for (std::size_t k = 0; k < kept; ++k) {
    out[k] = scored[k].second;
    included = included || out[k] == include;
  }
  for (std::size_t k = kept; k < std::size_t(count); ++k) out[k] = -1;
  if (!included) {
    if (kept < std::size_t(count))
      out[kept] = include;
    else
      out[count - 1] = include;
  }
}

}  // namespace

std::uint64_t candidate_search_bytes(int clusters, int terms, int lights, unsigned threads) {
  const std::uint64_t vectors = std::uint64_t(clusters) * terms;
  const std::uint64_t block = std::uint64_t(projected_rows_per_task(vectors)) * vectors * sizeof(float);
  const std::uint64_t scored = std::uint64_t(clusters) * sizeof(std::pair<float, std::int32_t>);
  return vectors * lights * sizeof(float) + std::uint64_t(std::max(1u, threads)) * (block + scored);
}

double AssignmentResult::total_objective() const {
  double total = 0;
  for (const float value : objective) total += value;
  return total;
}

CandidateLists nearest_subspace_candidates(const WorkingRows& rows, const ClusterModel& model,
                                           const CandidateOptions& options, unsigned threads) {
  const int terms = model.terms, lights = model.lights, clusters = model.clusters;
  const int count = std::max(1, options.count);
  // Q_all = [Q_0 ... Q_{K-1}], lights x (clusters * terms).
  Eigen::MatrixXf q_all(lights, std::size_t(clusters) * terms);
  for (int k = 0; k < clusters; ++k)
    q_all.middleCols(std::size_t(k) * terms, terms) =
        orthonormal_columns(model.basis(k), terms, lights);
  const auto allowed = [&](std::int32_t k) {
    return !options.allowed || (*options.allowed)[static_cast<std::size_t>(k)] != 0;
  };

  CandidateLists lists;
  lists.width = count;
  lists.clusters.assign(rows.rows() * count, -1);
  const std::size_t per_task = projected_rows_per_task(std::uint64_t(clusters) * terms);
  parallel_for(task_count(rows.rows(), per_task), threads, [&](std::size_t task, unsigned) {
    const std::size_t begin = task * per_task;
    const std::size_t end = std::min(rows.rows(), begin + per_task);
    std::vector<std::pair<float, std::int32_t>> scored;
    Eigen::MatrixXf projections;
    const bool dense = !options.pool;
    if (dense) projections = rows.values.middleRows(begin, end - begin) * q_all;  // rows x (K t)
    for (std::size_t r = begin; r < end; ++r) {
      throw_if_interrupted();  // a row scores every cluster: 100,000 of them take a while
      const auto x = rows.values.row(r);
      scored.clear();
      const auto score = [&](std::int32_t k, float energy) {
        scored.emplace_back(x.squaredNorm() - energy, k);
      };
      const std::int32_t* pool = options.pool ? options.pool->row(r) : nullptr;
      const bool pool_empty = pool == nullptr || pool[0] < 0;
      if (dense || pool_empty) {
        for (std::int32_t k = 0; k < clusters; ++k) {
          if (!allowed(k)) continue;
          float energy = 0;
          for (int j = 0; j < terms; ++j) {
            const float p = dense ? projections(r - begin, k * terms + j)
                                  : x.dot(q_all.col(k * terms + j).transpose());
            energy += p * p;
          }
          score(k, energy);
        }
      } else {
        for (int slot = 0; slot < options.pool->width && pool[slot] >= 0; ++slot) {
          const std::int32_t k = pool[slot];
          if (!allowed(k)) continue;
          float energy = 0;
          for (int j = 0; j < terms; ++j) {
            const float p = x.dot(q_all.col(k * terms + j).transpose());
            energy += p * p;
          }
          score(k, energy);
        }
      }
      const std::int32_t include =
          options.always_include ? (*options.always_include)[r] : std::int32_t(-1);
      write_best(scored, count, include >= 0 && allowed(include) ? include : -1,
                 lists.clusters.data() + r * count);
    }
  });
  return lists;
}

AssignmentResult assign_to_best_cluster(const WorkingRows& rows, const ClusterModel& model,
                                        const CandidateLists& candidates,
                                        const IrlsSettings& settings, unsigned threads,
                                        ProgressReporter* progress) {
  const std::size_t count = rows.rows();
  const int terms = model.terms, lights = model.lights;
  AssignmentResult result;
  result.best.assign(count, -1);
  result.second.assign(count, -1);
  result.objective.assign(count, 0.0f);
  result.weights.setZero(static_cast<Eigen::Index>(count), terms);
  std::vector<FunctionFitScratch> scratch(resolve_thread_count(threads));
  parallel_for(task_count(count), threads, [&](std::size_t task, unsigned worker) {
    const std::size_t begin = task * rows_per_task;
    const std::size_t end = std::min(count, begin + rows_per_task);
    float weights[max_cluster_terms];
    for (std::size_t r = begin; r < end; ++r) {
      throw_if_interrupted();
      const std::int32_t* list = candidates.row(r);
      float best = HUGE_VALF, second = HUGE_VALF;
      for (int slot = 0; slot < candidates.width && list[slot] >= 0; ++slot) {
        const std::int32_t k = list[slot];
        const float objective = fit_function_l1(model.basis(k), terms, lights, rows.row(r), 1.0f,
                                                settings, weights, scratch[worker]);
        if (objective < best) {
          second = best;
          result.second[r] = result.best[r];
          best = objective;
          result.best[r] = k;
          std::copy(weights, weights + terms, result.weights.row(r).data());
        } else if (objective < second) {
          second = objective;
          result.second[r] = k;
        }
      }
      result.objective[r] = best == HUGE_VALF ? 0.0f : best;
    }
    if (progress) progress->advance(end - begin);
  });
  return result;
}

}  // namespace relume
