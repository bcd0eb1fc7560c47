// The paper's results reproduced on one field, relume against clustered PCA (`relume eval`): for
// every (clusters, terms) of a grid the L1 method, clustered PCA (two forms) and the L1 method
// refitted for small residual budgets are made on the same rows (eval/grid_runs.hpp); measured are
// their Eq. 16 error against residual entries over all functions and the two classes
// (eval/function_classes.hpp), the ratio of clustered PCA's error to theirs, the sparseness of
// the residual, a per-pixel error difference, rate against distortion as the containers store
// them, and relighting speed, error and images (OpenCL, eval/relighting_measures.hpp). The rows
// are returned as numbers; writing them (CSV, NPY, PNG, JSON, plots) is the command's.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <relume/field.hpp>
#include <relume/lighting.hpp>
#include <string>
#include <vector>

#include "compress/noise_model.hpp"
#include "eval/evaluation_options.hpp"
#include "eval/function_classes.hpp"
#include "eval/grid_runs.hpp"
#include "eval/relighting_measures.hpp"
#include "model/field_psnr.hpp"

namespace relume {

// A mean of per-function errors over all stored functions and over each class (NaN for an empty
// class).
struct SubsetErrors {
  double all = 0, diffuse = NAN, specular = NAN;
};

// One run of the grid at one residual cap of EvaluationOptions::entries (paper Fig. 4 a-c).
struct ErrorPoint {
  std::size_t run = 0;  // in EvaluationResult::runs
  int entries = 0;      // kept per function: the cap, or an l1-refit run's budget
  SubsetErrors error;
};

// Clustered PCA's error over a method's, one configuration at one cap (paper Fig. 5): above 1,
// the method is better; NaN where the method's error is 0.
struct ErrorRatio {
  int clusters = 0, terms = 0, entries = 0;
  std::string method;  // "l1" or "l1-refit"
  SubsetErrors ratio;
};

// The fraction of a run's residual entries (none kept) at or below a threshold times the
// function's norm (paper Fig. 4d); for the runs with their full residual, not the refits.
struct SparsenessPoint {
  std::size_t run = 0;
  double threshold = 0, fraction = 0;
};

// One run stored as a container with a residual budget (rate against distortion).
struct RatePoint {
  std::size_t run = 0;
  int entries = 0;
  std::uint64_t bytes = 0;     // of the container file
  double bytes_per_pixel = 0;  // over the whole frame
  double ratio = 0;            // bytes over the field as float32
  double error_masked = 0;     // Eq. 16 of the stored values, inside the mask
  Psnr8 psnr;                  // 8-bit PSNR, masked and whole frame
};

// The primary configuration's per-pixel difference of clustered PCA's error minus the L1 method's
// at compare_entries, the mean over a pixel's stored functions (height x width, NaN where none is
// stored; paper Fig. 6).
struct ErrorDifference {
  Eigen::MatrixXd l1;
  Eigen::MatrixXd l1_refit;   // against the l1-refit run for compare_entries; empty without one
  std::size_t pixels = 0;     // with a stored function
  std::size_t l1_better = 0;  // of those, where l1's error is below clustered PCA's
};

// The error over all functions of each method of one configuration, in the order of
// evaluation_methods (l1-refit: its run for those entries).
struct MethodErrors {
  int entries = 0;
  std::vector<std::pair<std::string, double>> errors;
};

// One configuration's headline: its errors without residual and at compare_entries.
struct ConfigurationErrors {
  int clusters = 0, terms = 0;
  MethodErrors without_residual, at_compare_entries;
};

struct EvaluationResult {
  EvaluationOptions settings;  // as run (resolve_evaluation_options)
  std::string assignment;      // where the L1 reassignment ran: "cpu" or the OpenCL device
  std::size_t stored_functions = 0, dark_pixels = 0;
  NoiseModel noise;              // estimated from the field (compress's default)
  float residual_threshold = 0;  // residual entries at or below it are dropped
  FunctionClasses classes;       // per stored function
  std::vector<EvalRun> runs;     // in grid order (run_grid)
  std::vector<ErrorPoint> errors;
  std::vector<ErrorRatio> ratios;
  std::vector<SparsenessPoint> sparseness;
  ErrorDifference difference;
  std::vector<RatePoint> rate;
  // The primary configuration's l1 and cpca as stored with their longest cap, relit at every
  // cap; its l1-refit for compare_entries, when run, only relit once for its image.
  RelightingResult relighting;
  std::vector<ConfigurationErrors> configurations;  // in grid order
};

// Evaluates `field` as `options` ask, relighting it under `map`. Reports progress through the
// listener of options.progress (a bar on stderr only for the containers, unless options.quiet)
// and tells options' hooks as it goes; interruptible (lib/core/interruption.hpp). Throws Error
// as resolve_evaluation_options, for terms not below the field's lights, for a field without a
// function to store, and when OpenCL (the relighting, an "opencl" assignment) is not there.
EvaluationResult evaluate_field(const ReflectanceField& field, const EnvironmentMap& map,
                                const EvaluationOptions& options);

}  // namespace relume
