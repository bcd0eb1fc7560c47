// What the evaluation of one field (eval/evaluation.hpp, `relume eval`) sweeps and how it measures,
// each default held here once: the grid of (clusters, terms), the methods, the residual entries
// the errors are measured at, the refit budgets, the configuration of the per-pixel map, the
// relighting and the images, the storage of the containers; and the checks of those settings.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "compress/clustered_pca.hpp"
#include "core/progress.hpp"
#include "eval/function_classes.hpp"
#include "eval/grid_runs.hpp"
#include "eval/relighting_measures.hpp"
#include "model/quantization.hpp"

namespace relume {

// The methods an evaluation can run, in the order of its runs: l1 (relume's), cpca (clustered
// PCA, terms components), cpca-mean (a mean plus terms - 1 components), l1-refit (l1 refitted for
// each refit budget).
inline const std::vector<std::string> evaluation_methods = {"l1", "cpca", "cpca-mean", "l1-refit"};

struct EvaluationOptions {
  std::vector<int> clusters{32, 64}, terms{2, 4};   // the grid
  std::vector<int> entries{0, 1, 2, 3, 5, 10, 20};  // residual entries the errors are measured at
  std::vector<int> refit_entries{0, 1, 2, 3, 5};    // budgets an l1-refit run is made for
  int refit_rounds = 2;                             // of the trimmed least-squares refit
  std::vector<int> rate_entries;  // budgets of the rate-distortion containers; empty: entries
  std::vector<std::string> methods = evaluation_methods;  // l1 and cpca are required
  // The configuration of the per-pixel map, the relighting and the images; 0: the largest
  // clusters and terms of the grid.
  int primary_clusters = 0, primary_terms = 0;
  int compare_entries = 5;  // residual entries of the per-pixel map and the relit images
  int pca_iterations = ClusteredPcaOptions{}.iterations;
  double rotate_degrees = 0;  // of the environment map about +y, first frame
  int frames = RelightingSetup{}.frames;
  int timed_calls = RelightingSetup{}.timed_calls;
  std::string device;               // OpenCL device of the relighting and the L1 assignment
  std::string assign = "opencl";    // where the L1 reassignment fits run: "opencl" or "cpu"
  double diffuse_threshold = 0.02;  // energy fraction (eval/function_classes.hpp)
  double psnr_white = 1.0;          // the field value that is 255 in the 8-bit PSNR
  double quantization_budget = QuantizationBudget{}.relative_increase;  // of the containers
  std::uint64_t seed = 1;                                               // of the cluster seeding
  unsigned threads = 0;                                                 // 0: all cores

  bool quiet = true;  // no progress bar on stderr while the containers are stored
  // The listener of every step's progress (lib/core/progress.hpp), installed for the call; empty:
  // none. Each step can be interrupted (lib/core/interruption.hpp).
  ProgressListener progress;
  // Told as the work goes, on the calling thread; empty: not told. The stored functions and their
  // classes once found; each run of the grid as it ends; each relit cap as it is measured.
  std::function<void(std::size_t stored_functions, const FunctionClasses& classes)> on_classes;
  std::function<void(const EvalRun& run)> on_run;
  std::function<void(const RelightingRow& row)> on_relit;
};

// `options` checked and completed as the evaluation runs them: every list ascending without
// repeats, rate_entries filled from entries when empty, refit_entries empty without l1-refit, the
// primary configuration chosen. Throws Error naming the option (as `relume eval` spells it) and
// the value at fault; what needs the field (terms below its lights) is checked by the evaluation.
EvaluationOptions resolve_evaluation_options(EvaluationOptions options);

}  // namespace relume
