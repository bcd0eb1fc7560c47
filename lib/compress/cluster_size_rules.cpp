// Implementation of the cluster size rules (see cluster_size_rules.hpp).
#include "compress/cluster_size_rules.hpp"

#include <algorithm>
#include <numeric>
#include <relume/error.hpp>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_basis.hpp"
#include "compress/leading_subspace.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace {

// Moves the rows of clusters with fewer than `minimum` rows to their best surviving cluster.
void merge_small_clusters(const WorkingRows& rows, ClusterModel& model, int minimum, int candidates,
                          const IrlsSettings& settings, unsigned threads,
                          SizeRuleChanges& changes) {
  std::vector<std::size_t> size(std::size_t(model.clusters), 0);
  for (const std::int32_t k : model.assignment) ++size[static_cast<std::size_t>(k)];
  const std::size_t largest =
      static_cast<std::size_t>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<std::uint8_t> survives(size.size(), 1);
  for (std::size_t k = 0; k < size.size(); ++k) {
    if (k != largest && size[k] < std::size_t(std::max(minimum, 1))) {
      survives[k] = 0;
      ++changes.merged;
    }
  }
  // Rows of dissolved clusters, refitted against the surviving clusters only.
  std::vector<std::uint32_t> moved;
  for (std::size_t r = 0; r < model.assignment.size(); ++r)
    if (!survives[static_cast<std::size_t>(model.assignment[r])]) moved.push_back(std::uint32_t(r));
  if (!moved.empty()) {
    WorkingRows subset;
    subset.values.resize(static_cast<Eigen::Index>(moved.size()), rows.lights());
    subset.norms.assign(moved.size(), 1.0f);
    for (std::size_t k = 0; k < moved.size(); ++k)
      subset.values.row(static_cast<Eigen::Index>(k)) = rows.values.row(moved[k]);
    CandidateOptions options;
    options.count = candidates;
    options.allowed = &survives;
    const CandidateLists lists = nearest_subspace_candidates(subset, model, options, threads);
    const AssignmentResult result = assign_to_best_cluster(subset, model, lists, settings, threads);
    for (std::size_t k = 0; k < moved.size(); ++k) {
      model.assignment[moved[k]] = result.best[k];
      model.weights.row(moved[k]) = result.weights.row(static_cast<Eigen::Index>(k));
    }
    changes.rows_moved += moved.size();
  }
  // Renumber the surviving clusters densely.
  std::vector<std::int32_t> new_id(size.size(), -1);
  std::vector<float> bases;
  int clusters = 0;
  for (std::size_t k = 0; k < size.size(); ++k) {
    if (!survives[k]) continue;
    new_id[k] = clusters++;
    const float* basis = model.basis(static_cast<int>(k));
    bases.insert(bases.end(), basis, basis + std::size_t(model.terms) * model.lights);
  }
  for (std::int32_t& k : model.assignment) k = new_id[static_cast<std::size_t>(k)];
  model.bases = std::move(bases);
  model.clusters = clusters;
}

// Splits `members` of cluster k at the median of their coordinate along the direction the
// cluster's basis explains worst; returns the half that moves to a new cluster.
std::vector<std::uint32_t> split_off_half(const WorkingRows& rows, const ClusterModel& model, int k,
                                          std::vector<std::uint32_t>& members) {
  const Eigen::MatrixXf q = orthonormal_columns(model.basis(k), model.terms, model.lights);
  RowMatrixF leftover(static_cast<Eigen::Index>(members.size()), model.lights);
  for (std::size_t p = 0; p < members.size(); ++p) {
    const auto x = rows.values.row(members[p]);
    leftover.row(static_cast<Eigen::Index>(p)) = x - (x * q) * q.transpose();
  }
  const Eigen::VectorXf direction =
      leading_right_singular_vectors(leftover, 1).row(0).transpose().cast<float>();
  const Eigen::VectorXf score = leftover * direction;
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const std::size_t half = members.size() / 2;
  std::nth_element(order.begin(), order.begin() + half, order.end(),
                   [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
  std::vector<std::uint32_t> kept, moved;
  for (std::size_t i = 0; i < order.size(); ++i)
    (i < half ? kept : moved).push_back(members[order[i]]);
  std::sort(kept.begin(), kept.end());
  std::sort(moved.begin(), moved.end());
  members = std::move(kept);
  return moved;
}

void split_large_clusters(const WorkingRows& rows, ClusterModel& model, int maximum,
                          const IrlsSettings& settings, unsigned threads,
                          SizeRuleChanges& changes) {
  auto members = model.members();
  std::vector<int> refit;  // clusters whose rows changed
  for (int k = 0; k < model.clusters; ++k) {
    while (members[k].size() > std::size_t(maximum)) {
      std::vector<std::uint32_t> moved = split_off_half(rows, model, k, members[k]);
      const int added = model.clusters++;
      model.bases.resize(std::size_t(model.clusters) * model.terms * model.lights);
      for (const std::uint32_t r : moved) model.assignment[r] = added;
      members.push_back(std::move(moved));
      refit.push_back(k);
      refit.push_back(added);
      ++changes.split;
    }
  }
  std::sort(refit.begin(), refit.end());
  refit.erase(std::unique(refit.begin(), refit.end()), refit.end());
  for (const int k : refit) {
    // Clusters split again later are refitted once, with their final members.
    const std::vector<float> basis = least_squares_subspace(rows, members[k], model.terms);
    std::copy(basis.begin(), basis.end(), model.basis(k));
  }
  std::vector<FunctionFitScratch> scratch(resolve_thread_count(threads));
  for (const int k : refit) {
    const auto& list = members[static_cast<std::size_t>(k)];
    parallel_for(list.size(), threads, [&](std::size_t i, unsigned worker) {
      const std::uint32_t r = list[i];
      fit_function_l1(model.basis(k), model.terms, model.lights, rows.row(r), 1.0f, settings,
                      model.weights.row(r).data(), scratch[worker]);
    });
    changes.rows_moved += list.size();
  }
}

}  // namespace

void validate_size_limits(const ClusterSizeLimits& limits, int terms) {
  if (limits.minimum < -1 || limits.maximum < 0)
    throw Error("cluster size limits must be >= 0, got minimum " + std::to_string(limits.minimum) +
                " and maximum " + std::to_string(limits.maximum));
  const int minimum = limits.minimum_for(terms);
  if (limits.maximum > 0 && limits.maximum < 2 * std::max(minimum, 1))
    throw Error("maximum cluster size " + std::to_string(limits.maximum) +
                " must be at least twice the minimum (" + std::to_string(minimum) +
                ") so that split halves are not merged again (or 0 for no maximum)");
}

SizeRuleChanges enforce_cluster_sizes(const WorkingRows& rows, ClusterModel& model,
                                      const ClusterSizeLimits& limits, int candidates,
                                      const IrlsSettings& settings, unsigned threads) {
  SizeRuleChanges changes;
  if (model.clusters == 0) return changes;
  merge_small_clusters(rows, model, limits.minimum_for(model.terms), candidates, settings, threads,
                       changes);
  if (limits.maximum > 0)
    split_large_clusters(rows, model, limits.maximum, settings, threads, changes);
  return changes;
}

}  // namespace relume
