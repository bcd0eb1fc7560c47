// Trimmed least-squares refit of a clustering for its residual budget: the step that lets the
// L1 method win where the paper concedes it loses, with no or few residual entries.
//
// A stored function keeps the n largest entries of its residual, so its error (paper Eq. 16, on
// the unit-norm rows) is the sum of its squared residual over the other lights. Neither the L1
// fit (a sparse-residual surrogate) nor least squares (n = 0 only) minimises that for n > 0;
// this refit does, by descent from the model it is given:
//   - the weights of a row: least trimmed squares, alternating "keep the n largest |residual|"
//     and "least squares over the other lights" (G = F F^T minus the kept lights' outer
//     products), from the least-squares fit and, in its own cluster, from its current weights;
//   - the reassignment: each row goes to the candidate cluster (the current one and the nearest
//     by least-squares projection) whose trimmed fit is smallest;
//   - the basis step: every light's column of F^k by least squares over the cluster's rows that
//     do not keep that light, with W fixed.
// Every step lowers (never raises) the sum of the rows' trimmed errors, so the result is at
// least as good as its start at n entries. With n = 0 it is clustered least squares (k-subspaces)
// started from the L1 clustering.
#pragma once

#include <optional>
#include <vector>

#include "compress/cluster_model.hpp"

namespace relume {

struct TrimmedRefitOptions {
  int entries = 0;     // residual entries every row keeps (n)
  int rounds = 2;      // basis step + reassignment rounds (0: the reassignment alone)
  int candidates = 3;  // clusters tried per row besides its own
  int fit_steps = 4;   // alternations of the kept set and the weights per fit
  unsigned threads = 0;
  bool quiet = false;
};

struct TrimmedRefitTrace {
  // With clusters chosen from two clusterings (choose_clusters): the sum of the trimmed errors of
  // the method's own clustering, before the choice.
  std::optional<double> objective_before_choice;
  double objective_before = 0;          // sum over rows of the trimmed squared error
  std::vector<double> objective_after;  // after every round
  std::size_t changed = 0;              // rows that changed cluster, over all rounds
  int clusters_removed = 0;             // clusters left without rows
  double seconds = 0;
};

// Refits `model` (bases, assignment and weights all set) in place.
void refit_trimmed_least_squares(const WorkingRows& rows, ClusterModel& model,
                                 const TrimmedRefitOptions& options, TrimmedRefitTrace& trace);

// Chooses per cluster between two clusterings of the same rows (same terms and lights): every
// row is offered the union of both sets of bases (its `options.candidates` + 2 nearest by
// least-squares projection and its own cluster in each), fitted by least trimmed squares for
// `options.entries`, and the cluster whose removal raises the sum of the rows' trimmed errors
// least (each of its rows moving to its next-best cluster still there) is removed, one at a time,
// until as many clusters remain as `first` has. Returns that model with every row's weights, or
// the better input where it is not lower; `objective` receives its sum of trimmed errors.
ClusterModel choose_clusters(const WorkingRows& rows, const ClusterModel& first,
                             const ClusterModel& second, const TrimmedRefitOptions& options,
                             double& objective);

// The trimmed squared error of every row of `model`: the sum of its squared residual with its
// `entries` largest |entries| left out.
std::vector<double> trimmed_errors(const WorkingRows& rows, const ClusterModel& model, int entries,
                                   unsigned threads);

}  // namespace relume
