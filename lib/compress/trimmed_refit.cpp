// Implementation of the trimmed least-squares refit (see trimmed_refit.hpp). Interruptible
// where it reports progress.
#include "compress/trimmed_refit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <relume/error.hpp>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_basis.hpp"
#include "compress/cluster_function_fit.hpp"
#include "core/elapsed_time.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

constexpr std::size_t rows_per_task = 512;

// Working memory of one thread.
struct TrimmedScratch {
  std::vector<double> residual;
  std::vector<int> order;  // after trimmed_sum: the kept lights first
};

// x - w F into scratch.residual.
void compute_residual(const float* basis, int terms, int lights, const float* x, const double* w,
                      TrimmedScratch& scratch) {
  scratch.residual.resize(lights);
  for (int i = 0; i < lights; ++i) scratch.residual[i] = x[i];
  for (int j = 0; j < terms; ++j) {
    const float* f = basis + std::size_t(j) * lights;
    for (int i = 0; i < lights; ++i) scratch.residual[i] -= w[j] * f[i];
  }
}

// The squared residual summed over every light but the `kept` largest |residual|, whose lights
// end up in scratch.order[0, kept).
double trimmed_sum(int lights, int kept, TrimmedScratch& scratch) {
  const std::vector<double>& r = scratch.residual;
  scratch.order.resize(lights);
  std::iota(scratch.order.begin(), scratch.order.end(), 0);
  kept = std::clamp(kept, 0, lights);
  if (kept > 0 && kept < lights)
    std::nth_element(scratch.order.begin(), scratch.order.begin() + (kept - 1), scratch.order.end(),
                     [&](int a, int b) { return std::fabs(r[a]) > std::fabs(r[b]); });
  double sum = 0;
  for (int e = kept; e < lights; ++e) sum += r[scratch.order[e]] * r[scratch.order[e]];
  return sum;
}

// F F^T of one cluster's basis (t x t, row-major).
std::vector<double> basis_gram(const float* basis, int terms, int lights) {
  std::vector<double> gram(std::size_t(terms) * terms, 0.0);
  for (int j = 0; j < terms; ++j)
    for (int l = 0; l <= j; ++l) {
      double sum = 0;
      for (int i = 0; i < lights; ++i)
        sum += double(basis[std::size_t(j) * lights + i]) * basis[std::size_t(l) * lights + i];
      gram[j * terms + l] = gram[l * terms + j] = sum;
    }
  return gram;
}

// Least trimmed squares weights of row x against one basis (see trimmed_refit.hpp).
class TrimmedRowFit {
 public:
  TrimmedRowFit(const float* basis, const double* gram, int terms, int lights, int kept, int steps,
                const float* x, TrimmedScratch& scratch)
      : basis_(basis),
        gram_(gram),
        terms_(terms),
        lights_(lights),
        kept_(kept),
        steps_(steps),
        x_(x),
        scratch_(scratch) {
    for (int j = 0; j < terms; ++j) {
      double sum = 0;
      for (int i = 0; i < lights; ++i) sum += double(basis[std::size_t(j) * lights + i]) * x[i];
      fx_[j] = sum;
    }
  }

  // Descends from `start` (the least-squares fit when null) into `weights`; returns the
  // trimmed squared error.
  double fit(const float* start, double* weights) {
    if (start)
      std::copy(start, start + terms_, weights);
    else
      solve_excluding(0, weights);
    compute_residual(basis_, terms_, lights_, x_, weights, scratch_);
    double objective = trimmed_sum(lights_, kept_, scratch_);
    double trial[max_cluster_terms];
    for (int step = 0; step < steps_ && kept_ > 0; ++step) {
      solve_excluding(kept_, trial);
      compute_residual(basis_, terms_, lights_, x_, trial, scratch_);
      const double next = trimmed_sum(lights_, kept_, scratch_);
      if (!(next < objective)) break;
      objective = next;
      std::copy(trial, trial + terms_, weights);
    }
    return objective;
  }

 private:
  // Least squares over the lights but the first `excluded` of scratch.order.
  void solve_excluding(int excluded, double* out) {
    double g[max_cluster_terms * max_cluster_terms];
    std::copy(gram_, gram_ + terms_ * terms_, g);
    std::copy(fx_, fx_ + terms_, out);
    for (int e = 0; e < excluded; ++e) {
      const int i = scratch_.order[e];
      for (int j = 0; j < terms_; ++j) {
        const double fj = basis_[std::size_t(j) * lights_ + i];
        out[j] -= fj * x_[i];
        for (int l = 0; l < terms_; ++l)
          g[j * terms_ + l] -= fj * basis_[std::size_t(l) * lights_ + i];
      }
    }
    solve_small_spd(g, out, terms_);
  }

  const float* basis_;
  const double* gram_;
  int terms_, lights_, kept_, steps_;
  const float* x_;
  TrimmedScratch& scratch_;
  double fx_[max_cluster_terms];
};

// The subspace step of cluster k (EM for PCA with missing values): every member's kept lights
// are filled in with its current fit, F^k becomes the least-squares subspace of the filled-in
// rows (orthonormal) and W their projections on it. With the kept set fixed this cannot raise the
// trimmed error (the filled-in values cost nothing before and at most their own squares after);
// kept only when it lowers it. With no residual it is clustered PCA's fit of the cluster.
void refit_cluster_subspace(const WorkingRows& rows, const std::vector<std::uint32_t>& members,
                            int kept, ClusterModel& model, int k, TrimmedScratch& scratch) {
  const int terms = model.terms, lights = model.lights;
  if (members.size() < std::size_t(terms)) return;
  float* basis = model.basis(k);
  WorkingRows filled;
  filled.values.resize(static_cast<Eigen::Index>(members.size()), lights);
  filled.norms.assign(members.size(), 1.0f);
  double before = 0;
  double w[max_cluster_terms];
  for (std::size_t m = 0; m < members.size(); ++m) {
    const std::uint32_t p = members[m];
    const float* x = rows.row(p);
    for (int j = 0; j < terms; ++j) w[j] = model.weights(p, j);
    compute_residual(basis, terms, lights, x, w, scratch);
    before += trimmed_sum(lights, kept, scratch);
    float* out = filled.values.row(static_cast<Eigen::Index>(m)).data();
    std::copy(x, x + lights, out);
    for (int e = 0; e < std::min(kept, lights); ++e) {
      const int i = scratch.order[e];
      out[i] = static_cast<float>(x[i] - scratch.residual[i]);
    }
  }
  std::vector<std::uint32_t> all(members.size());
  std::iota(all.begin(), all.end(), 0u);
  const std::vector<float> subspace = least_squares_subspace(filled, all, terms);
  const Eigen::Map<const RowMatrixF> f(subspace.data(), terms, lights);
  const RowMatrixF projected = filled.values * f.transpose();  // members x terms
  double after = 0;
  for (std::size_t m = 0; m < members.size(); ++m) {
    for (int j = 0; j < terms; ++j) w[j] = projected(static_cast<Eigen::Index>(m), j);
    compute_residual(subspace.data(), terms, lights, rows.row(members[m]), w, scratch);
    after += trimmed_sum(lights, kept, scratch);
  }
  if (!(after < before)) return;
  std::copy(subspace.begin(), subspace.end(), basis);
  for (std::size_t m = 0; m < members.size(); ++m)
    model.weights.row(members[m]) = projected.row(static_cast<Eigen::Index>(m));
}

// The basis step of cluster k: every light's column of F^k by least squares over the members
// that do not keep that light, W fixed; rows then scaled to unit norm (W scaled inversely).
// Kept only when it lowers the cluster's trimmed error.
void refit_cluster_basis(const WorkingRows& rows, const std::vector<std::uint32_t>& members,
                         int kept, ClusterModel& model, int k, TrimmedScratch& scratch) {
  const int terms = model.terms, lights = model.lights;
  if (members.empty()) return;
  float* basis = model.basis(k);
  std::vector<double> gram_all(std::size_t(terms) * terms, 0.0);
  std::vector<double> rhs(std::size_t(terms) * lights, 0.0);
  std::vector<double> gram_kept(std::size_t(terms) * terms * lights, 0.0);
  std::vector<double> rhs_kept(std::size_t(terms) * lights, 0.0);
  double before = 0;
  double w[max_cluster_terms];
  for (const std::uint32_t p : members) {
    const float* x = rows.row(p);
    for (int j = 0; j < terms; ++j) w[j] = model.weights(p, j);
    compute_residual(basis, terms, lights, x, w, scratch);
    before += trimmed_sum(lights, kept, scratch);
    for (int j = 0; j < terms; ++j) {
      for (int l = 0; l < terms; ++l) gram_all[j * terms + l] += w[j] * w[l];
      for (int i = 0; i < lights; ++i) rhs[std::size_t(j) * lights + i] += w[j] * x[i];
    }
    for (int e = 0; e < std::min(kept, lights); ++e) {
      const int i = scratch.order[e];
      double* g = gram_kept.data() + std::size_t(i) * terms * terms;
      for (int j = 0; j < terms; ++j) {
        for (int l = 0; l < terms; ++l) g[j * terms + l] += w[j] * w[l];
        rhs_kept[std::size_t(j) * lights + i] += w[j] * x[i];
      }
    }
  }
  std::vector<float> fitted(std::size_t(terms) * lights);
  for (int i = 0; i < lights; ++i) {
    double g[max_cluster_terms * max_cluster_terms], b[max_cluster_terms];
    const double* g_kept = gram_kept.data() + std::size_t(i) * terms * terms;
    for (int j = 0; j < terms; ++j) {
      for (int l = 0; l < terms; ++l)
        g[j * terms + l] = gram_all[j * terms + l] - g_kept[j * terms + l];
      b[j] = rhs[std::size_t(j) * lights + i] - rhs_kept[std::size_t(j) * lights + i];
    }
    solve_small_spd(g, b, terms);
    for (int j = 0; j < terms; ++j) fitted[std::size_t(j) * lights + i] = static_cast<float>(b[j]);
  }
  double scale[max_cluster_terms];
  for (int j = 0; j < terms; ++j) {
    double norm = 0;
    for (int i = 0; i < lights; ++i)
      norm += double(fitted[std::size_t(j) * lights + i]) * fitted[std::size_t(j) * lights + i];
    norm = std::sqrt(norm);
    scale[j] = norm > 0 ? norm : 1.0;
    for (int i = 0; i < lights; ++i)
      fitted[std::size_t(j) * lights + i] =
          static_cast<float>(fitted[std::size_t(j) * lights + i] / scale[j]);
  }
  double after = 0;
  for (const std::uint32_t p : members) {
    for (int j = 0; j < terms; ++j) w[j] = double(model.weights(p, j)) * scale[j];
    compute_residual(fitted.data(), terms, lights, rows.row(p), w, scratch);
    after += trimmed_sum(lights, kept, scratch);
  }
  if (!(after < before)) return;
  std::copy(fitted.begin(), fitted.end(), basis);
  for (const std::uint32_t p : members)
    for (int j = 0; j < terms; ++j)
      model.weights(p, j) = static_cast<float>(model.weights(p, j) * scale[j]);
}

// Every row to the candidate cluster with the smallest trimmed fit (its weights refitted);
// returns the rows that changed cluster and adds the trimmed errors to `objective`.
std::size_t reassign_trimmed(const WorkingRows& rows, ClusterModel& model,
                             const TrimmedRefitOptions& options, double& objective,
                             ProgressReporter& progress) {
  const int terms = model.terms, lights = model.lights;
  CandidateOptions candidate_options;
  candidate_options.count = std::max(1, options.candidates);
  candidate_options.always_include = &model.assignment;
  const CandidateLists candidates =
      nearest_subspace_candidates(rows, model, candidate_options, options.threads);
  std::vector<std::vector<double>> grams(std::size_t(model.clusters));
  for (int k = 0; k < model.clusters; ++k) grams[k] = basis_gram(model.basis(k), terms, lights);

  const std::size_t count = rows.rows();
  const std::size_t tasks = (count + rows_per_task - 1) / rows_per_task;
  std::vector<std::int32_t> best_cluster(count);
  RowMatrixF best_weights(static_cast<Eigen::Index>(count), terms);
  std::vector<double> task_objective(tasks, 0.0);
  std::vector<TrimmedScratch> scratch(resolve_thread_count(options.threads));
  parallel_for(tasks, options.threads, [&](std::size_t task, unsigned worker) {
    const std::size_t begin = task * rows_per_task, end = std::min(count, begin + rows_per_task);
    double weights[max_cluster_terms], kept_weights[max_cluster_terms];
    for (std::size_t r = begin; r < end; ++r) {
      const std::int32_t own = model.assignment[r];
      double best = HUGE_VAL;
      std::int32_t chosen = own;
      const std::int32_t* list = candidates.row(r);
      for (int slot = 0; slot < candidates.width && list[slot] >= 0; ++slot) {
        const std::int32_t k = list[slot];
        TrimmedRowFit fit(model.basis(k), grams[k].data(), terms, lights, options.entries,
                          options.fit_steps, rows.row(r), scratch[worker]);
        for (int from = 0; from < (k == own ? 2 : 1); ++from) {
          const double value = fit.fit(from == 0 ? nullptr : model.weights.row(r).data(), weights);
          if (value < best || (value == best && k == own)) {
            best = value;
            chosen = k;
            std::copy(weights, weights + terms, kept_weights);
          }
        }
      }
      best_cluster[r] = chosen;
      for (int j = 0; j < terms; ++j) best_weights(r, j) = static_cast<float>(kept_weights[j]);
      task_objective[task] += best;
    }
    progress.advance(end - begin);
  });
  std::size_t changed = 0;
  for (std::size_t r = 0; r < count; ++r) changed += best_cluster[r] != model.assignment[r];
  for (const double value : task_objective) objective += value;
  model.assignment = std::move(best_cluster);
  model.weights = std::move(best_weights);
  return changed;
}

// Removes clusters without rows and renumbers the others densely; returns how many went.
int remove_empty_clusters(ClusterModel& model) {
  std::vector<std::size_t> size(std::size_t(model.clusters), 0);
  for (const std::int32_t k : model.assignment) ++size[static_cast<std::size_t>(k)];
  std::vector<std::int32_t> new_id(size.size(), -1);
  std::vector<float> bases;
  int clusters = 0;
  for (std::size_t k = 0; k < size.size(); ++k) {
    if (size[k] == 0) continue;
    new_id[k] = clusters++;
    const float* basis = model.basis(static_cast<int>(k));
    bases.insert(bases.end(), basis, basis + std::size_t(model.terms) * model.lights);
  }
  const int removed = model.clusters - clusters;
  for (std::int32_t& k : model.assignment) k = new_id[static_cast<std::size_t>(k)];
  model.bases = std::move(bases);
  model.clusters = clusters;
  return removed;
}

// The union of two clusterings' bases: `first`'s clusters, then `second`'s.
ClusterModel union_of(const ClusterModel& first, const ClusterModel& second) {
  ClusterModel both;
  both.terms = first.terms;
  both.lights = first.lights;
  both.clusters = first.clusters + second.clusters;
  both.bases = first.bases;
  both.bases.insert(both.bases.end(), second.bases.begin(), second.bases.end());
  both.assignment = first.assignment;
  return both;
}

}  // namespace

ClusterModel choose_clusters(const WorkingRows& rows, const ClusterModel& first,
                             const ClusterModel& second, const TrimmedRefitOptions& options,
                             double& objective) {
  if (first.terms != second.terms || first.lights != second.lights ||
      first.assignment.size() != rows.rows() || second.assignment.size() != rows.rows())
    throw Error("clusters can only be chosen between clusterings of the same rows and terms");
  const int terms = first.terms, lights = first.lights;
  const ClusterModel both = union_of(first, second);
  CandidateOptions candidate_options;
  candidate_options.count = std::max(1, options.candidates) + 2;
  candidate_options.always_include = &first.assignment;
  CandidateLists lists =
      nearest_subspace_candidates(rows, both, candidate_options, options.threads);
  const int width = lists.width;
  std::vector<std::vector<double>> grams(std::size_t(both.clusters));
  for (int k = 0; k < both.clusters; ++k) grams[k] = basis_gram(both.basis(k), terms, lights);

  // Every row's candidates sorted by their trimmed error, with the weights of each fit.
  const std::size_t count = rows.rows();
  std::vector<double> error(count * width, HUGE_VAL);
  std::vector<float> weights(count * width * terms, 0.0f);
  std::vector<TrimmedScratch> scratch(resolve_thread_count(options.threads));
  parallel_for(count, options.threads, [&](std::size_t r, unsigned worker) {
    std::int32_t* list = lists.clusters.data() + r * width;
    const std::int32_t own_second = first.clusters + second.assignment[r];
    if (std::find(list, list + width, own_second) == list + width) {
      std::int32_t* slot = std::find(list, list + width, std::int32_t(-1));
      if (slot == list + width)
        slot = list + width - (list[width - 1] == first.assignment[r] ? 2 : 1);
      *slot = own_second;
    }
    double fitted[max_cluster_terms];
    std::vector<std::pair<double, int>> order;
    std::vector<float> found(std::size_t(width) * terms);
    for (int slot = 0; slot < width; ++slot) {
      const std::int32_t k = list[slot];
      if (k < 0) continue;
      TrimmedRowFit fit(both.basis(k), grams[k].data(), terms, lights, options.entries,
                        options.fit_steps, rows.row(r), scratch[worker]);
      const float* own = k == first.assignment[r] ? first.weights.row(r).data()
                         : k == own_second        ? second.weights.row(r).data()
                                                  : nullptr;
      double best = fit.fit(nullptr, fitted);
      std::copy(fitted, fitted + terms, found.begin() + std::size_t(slot) * terms);
      if (own) {
        double from_own[max_cluster_terms];
        const double value = fit.fit(own, from_own);
        if (value < best) {
          best = value;
          std::copy(from_own, from_own + terms, found.begin() + std::size_t(slot) * terms);
        }
      }
      order.emplace_back(best, slot);
    }
    std::sort(order.begin(), order.end());
    std::vector<std::int32_t> sorted(width, -1);
    for (std::size_t e = 0; e < order.size(); ++e) {
      const int slot = order[e].second;
      sorted[e] = list[slot];
      error[r * width + e] = order[e].first;
      std::copy(found.begin() + std::size_t(slot) * terms,
                found.begin() + std::size_t(slot + 1) * terms,
                weights.begin() + (r * width + e) * terms);
    }
    std::copy(sorted.begin(), sorted.end(), list);
  });

  // Greedy removal down to first.clusters clusters. A row with no candidate left would fall back
  // to a cluster it was not fitted to: counted as losing its whole (unit) energy.
  std::vector<std::uint8_t> alive(std::size_t(both.clusters), 1);
  const auto first_alive = [&](std::size_t r, int from) {
    const std::int32_t* list = lists.clusters.data() + r * width;
    for (int e = from; e < width; ++e)
      if (list[e] >= 0 && alive[list[e]]) return e;
    return width;
  };
  for (int remaining = both.clusters; remaining > first.clusters; --remaining) {
    std::vector<double> cost(std::size_t(both.clusters), 0.0);
    for (std::size_t r = 0; r < count; ++r) {
      const int best = first_alive(r, 0);
      if (best == width) continue;
      const int next = first_alive(r, best + 1);
      const double rise = next == width ? 1.0 : error[r * width + next];
      cost[lists.clusters[r * width + best]] += rise - error[r * width + best];
    }
    int removed = -1;
    for (int k = 0; k < both.clusters; ++k)
      if (alive[k] && (removed < 0 || cost[k] < cost[removed])) removed = k;
    if (removed < 0) break;  // no cluster alive (cannot happen while remaining > 0)
    alive[removed] = 0;
  }

  ClusterModel chosen;
  chosen.terms = terms;
  chosen.lights = lights;
  std::vector<std::int32_t> new_id(std::size_t(both.clusters), -1);
  for (int k = 0; k < both.clusters; ++k) {
    if (!alive[k]) continue;
    new_id[k] = chosen.clusters++;
    chosen.bases.insert(chosen.bases.end(), both.basis(k),
                        both.basis(k) + std::size_t(terms) * lights);
  }
  chosen.assignment.assign(count, -1);
  chosen.weights.setZero(static_cast<Eigen::Index>(count), terms);
  std::vector<std::uint32_t> stranded;
  double total = 0;
  for (std::size_t r = 0; r < count; ++r) {
    const int best = first_alive(r, 0);
    if (best == width) {
      stranded.push_back(static_cast<std::uint32_t>(r));
      continue;
    }
    chosen.assignment[r] = new_id[lists.clusters[r * width + best]];
    for (int j = 0; j < terms; ++j)
      chosen.weights(static_cast<Eigen::Index>(r), j) = weights[(r * width + best) * terms + j];
    total += error[r * width + best];
  }
  // Rows whose candidates all went: their nearest chosen cluster by projection, fitted there.
  if (!stranded.empty()) {
    WorkingRows subset;
    subset.values.resize(static_cast<Eigen::Index>(stranded.size()), lights);
    subset.norms.assign(stranded.size(), 1.0f);
    for (std::size_t s = 0; s < stranded.size(); ++s)
      subset.values.row(static_cast<Eigen::Index>(s)) = rows.values.row(stranded[s]);
    CandidateOptions nearest;
    nearest.count = 1;
    const CandidateLists best =
        nearest_subspace_candidates(subset, chosen, nearest, options.threads);
    for (std::size_t s = 0; s < stranded.size(); ++s) {
      const std::int32_t k = best.clusters[s];
      const std::vector<double> gram = basis_gram(chosen.basis(k), terms, lights);
      TrimmedRowFit fit(chosen.basis(k), gram.data(), terms, lights, options.entries,
                        options.fit_steps, rows.row(stranded[s]), scratch[0]);
      double fitted[max_cluster_terms];
      total += fit.fit(nullptr, fitted);
      chosen.assignment[stranded[s]] = k;
      for (int j = 0; j < terms; ++j)
        chosen.weights(static_cast<Eigen::Index>(stranded[s]), j) = static_cast<float>(fitted[j]);
    }
  }
  // Never worse than either input.
  const auto sum = [&](const ClusterModel& model) {
    const std::vector<double> errors =
        trimmed_errors(rows, model, options.entries, options.threads);
    return std::accumulate(errors.begin(), errors.end(), 0.0);
  };
  const double first_total = sum(first), second_total = sum(second);
  objective = std::min({total, first_total, second_total});
  if (objective == total) {
    remove_empty_clusters(chosen);
    return chosen;
  }
  return objective == first_total ? first : second;
}

std::vector<double> trimmed_errors(const WorkingRows& rows, const ClusterModel& model, int entries,
                                   unsigned threads) {
  std::vector<double> errors(rows.rows());
  std::vector<TrimmedScratch> scratch(resolve_thread_count(threads));
  parallel_for(rows.rows(), threads, [&](std::size_t r, unsigned worker) {
    double w[max_cluster_terms];
    for (int j = 0; j < model.terms; ++j) w[j] = model.weights(static_cast<Eigen::Index>(r), j);
    compute_residual(model.basis(model.assignment[r]), model.terms, model.lights, rows.row(r), w,
                     scratch[worker]);
    errors[r] = trimmed_sum(model.lights, entries, scratch[worker]);
  });
  return errors;
}

void refit_trimmed_least_squares(const WorkingRows& rows, ClusterModel& model,
                                 const TrimmedRefitOptions& options, TrimmedRefitTrace& trace) {
  if (options.entries < 0 || options.rounds < 0 || options.fit_steps < 0 || options.candidates < 1)
    throw Error("trimmed refit settings out of range: entries " + std::to_string(options.entries) +
                ", rounds " + std::to_string(options.rounds) + ", fit steps " +
                std::to_string(options.fit_steps) + ", candidates " +
                std::to_string(options.candidates) + " (expected >= 0, >= 0, >= 0, >= 1)");
  if (model.clusters == 0 || rows.rows() == 0) return;
  const auto start = Clock::now();
  const std::vector<double> before = trimmed_errors(rows, model, options.entries, options.threads);
  trace.objective_before = std::accumulate(before.begin(), before.end(), 0.0);
  const int rounds = std::max(1, options.rounds);
  ProgressReporter progress("compress: trimmed least-squares refit",
                            std::uint64_t(rounds) * rows.rows(), options.quiet);
  for (int round = 0; round < rounds; ++round) {
    if (options.rounds > 0) {
      const auto members = model.members();
      std::vector<TrimmedScratch> scratch(resolve_thread_count(options.threads));
      parallel_for(std::size_t(model.clusters), options.threads,
                   [&](std::size_t k, unsigned worker) {
                     refit_cluster_subspace(rows, members[k], options.entries, model,
                                            static_cast<int>(k), scratch[worker]);
                     refit_cluster_basis(rows, members[k], options.entries, model,
                                         static_cast<int>(k), scratch[worker]);
                   });
    }
    double objective = 0;
    trace.changed += reassign_trimmed(rows, model, options, objective, progress);
    trace.objective_after.push_back(objective);
  }
  progress.finish();
  trace.clusters_removed = remove_empty_clusters(model);
  trace.seconds = seconds_since(start);
}

}  // namespace relume
