// The compressions the evaluation (`relume eval`) compares, all on the same prepared (unit-norm)
// rows: for every (clusters, terms) of its grid the L1 method (relume's default), clustered PCA
// without centring ("cpca", the stronger baseline at equal bytes) and with a mean ("cpca-mean",
// Sloan et al.), and the L1 method refitted by trimmed least squares for each residual budget of a
// list ("l1-refit"); and what is measured on every stored row of them.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "compress/clustered_factorization.hpp"

namespace relume {

struct EvalGrid {
  std::vector<int> clusters, terms;
  std::vector<int> refit_entries;  // budgets the l1-refit runs are made for
  int refit_rounds = 2;
  std::vector<std::string> methods;  // of "l1", "cpca", "cpca-mean", "l1-refit"
  ClusteringOptions clustering;      // everything but clusters and terms
  ClusteredPcaOptions pca;           // everything but the centring
};

struct EvalRun {
  std::string method;
  int clusters_asked = 0, terms = 0;
  int budget = -1;  // l1-refit: the residual entries it was refitted for; -1 for the others
  ClusterModel model;
  double seconds = 0;  // to make this model from the rows (l1-refit: the L1 run's plus its own)
  double refit_seconds = 0;  // l1-refit: the refit alone
  int iterations = 0;        // clustering iterations run
  TrimmedRefitTrace refit;   // l1-refit only
};

// Whether `methods` names `method`.
bool has_method(const std::vector<std::string>& methods, const std::string& method);

// Every run of the grid, in order: per (clusters, terms), l1, cpca, cpca-mean, then l1-refit per
// budget (only the methods asked for; l1-refit needs l1). `report` is told each run as it ends.
// Reports progress per (clusters, terms), printed unless grid.clustering.quiet; interruptible
// (between runs too).
std::vector<EvalRun> run_grid(const WorkingRows& rows, const EvalGrid& grid,
                              const std::function<void(const EvalRun&)>& report);

// Per stored row, its Eq. 16 term (squared error over its unit norm) when it keeps the `caps[c]`
// largest entries of its residual: rows x caps.
Eigen::MatrixXd row_errors(const WorkingRows& rows, const ClusterModel& model,
                           const std::vector<int>& caps, unsigned threads);

// Fraction of all residual entries (no entries kept) with |e| <= threshold x the row's norm, for
// every threshold (paper Fig. 4d).
std::vector<double> residual_sparseness(const WorkingRows& rows, const ClusterModel& model,
                                        const std::vector<double>& thresholds, unsigned threads);

}  // namespace relume
