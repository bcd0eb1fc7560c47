// relume/compress.hpp: clustered sparse residual factorization of a reflectance field (Yamada,
// Peers, Debevec):
//   R[p,:] ~ W[p,:] F^{c(p)} + E[p,:]
// The functions a scene needs (inside the mask, not all zero; each colour channel its own
// function) are clustered by L1 factorization (IRLS fits; the reassignment fits run on an OpenCL
// device or in C++), and each keeps its largest residual entries. The result is what
// relume/container.hpp stores and relume/relight.hpp relights. The `relume compress` command
// adds checkpoints with resume and JSON reports.
#pragma once

#include <cstdint>
#include <functional>
#include <relume/compressed_field.hpp>
#include <relume/container.hpp>
#include <relume/field.hpp>
#include <string>

namespace relume {

// The options of `relume compress` (its --help explains each), with the same defaults.
struct CompressOptions {
  int clusters = 64;  // K
  int terms = 4;      // t, basis functions per cluster (1 to 16)
  // Residual entries kept per function: `residual_entries` when >= 0, else residual_percent of
  // the lights.
  int residual_entries = -1;
  double residual_percent = 5.0;
  // Field units; negative: the field's noise floor (ReflectanceField::noise_floor). Pixels whose
  // every channel has an RMS at or below noise_floor share one dark model; residual entries with
  // |value| at or below residual_threshold are dropped.
  float noise_floor = -1.0f;
  float residual_threshold = -1.0f;
  BasisTransform transform = BasisTransform::identity;
  // Light weighting exponent in [0, 1]: > 0 fits each light's image relative to its own energy
  // (1: fully, 0.5: halfway), so that lights reaching the scene only at grazing angles keep their
  // accuracy; better relit images under concentrated back light, a higher Eq. 16 error. 0: the
  // paper's objective. Identity transform only.
  double light_weighting = 0;
  int multires_levels = 0;    // cluster a field downsampled 2x per level first
  int refine_iterations = 2;  // full-resolution iterations after multi-resolution clustering
  int iterations = 4;         // cap on L1 iterations (F-step + reassignment)
  int candidates = 3;         // clusters given the exact L1 fit per function
  int irls_iterations = 5;    // reweighted solves of every IRLS L1 fit
  int min_cluster_size = -1;  // smaller clusters merge away; -1 = max(8, 2 * terms)
  int max_cluster_size = 0;   // larger clusters split; 0 = no limit
  // "irls": the IRLS fits only; "lp-dual", "lp" or "huber": refit every cluster's F and W
  // exactly with that solver after the iterations.
  std::string solver = "irls";
  std::uint64_t seed = 1;  // of the cluster seeding
  unsigned threads = 0;    // 0 = all cores
  // Reassignment fits on this OpenCL device (see RelighterOptions::device); false: the C++ path.
  bool opencl_assignment = true;
  std::string device;
  // > 0: choose terms and clusters from a small grid and per-function residual lengths that reach
  // this relative error (paper Eq. 16, masked functions) with the fewest container bytes, counted
  // as stored with the precisions below (`relume compress --target-error`); clusters, terms and
  // the residual budget above are then not used.
  double target_error = 0;
  // How the result is stored (what compress returns is what the container holds): quantized
  // (integers times the coarsest steps within quantization_budget), float32 or float16.
  ValuePrecision weights_precision = ValuePrecision::quantized;
  ValuePrecision residual_precision = ValuePrecision::quantized;
  bool quantize_bases = true;         // 8 to 16 bits per basis value, a scale per basis row
  double quantization_budget = 0.01;  // what quantization may add to the Eq. 16 error, relative
  // With quantized storage: what dropping the basis terms that clusters of dim or simple
  // functions do not need may add to the Eq. 16 error, relative; 0 (the default: on the data
  // measured, one residual entry fewer saves bytes more cheaply) keeps every term.
  double term_budget = 0;
  bool quiet = true;  // no progress lines on stderr
  // Told (phase, fraction of it done in [0, 1]) at the start and end of each phase and about
  // every 0.1 s in between, on the thread that called compress(), e.g. ("compress: iteration 2,
  // assigning", 0.4). An exception it throws ends compress() and propagates: throw Interrupted
  // (relume/error.hpp) to stop it as Ctrl-C would.
  std::function<void(const std::string& phase, double fraction)> progress;
};

// Throws Error for options out of range or a field with nothing to store, Interrupted when an
// interruption was requested (lib/core/interruption.hpp, e.g. by a Ctrl-C handler).
CompressedField compress(const ReflectanceField& field, const CompressOptions& options = {});

}  // namespace relume
