// relume/compress.hpp: clustered sparse residual factorization of a reflectance field (Yamada,
// Peers, Debevec):
//   R[p,:] ~ W[p,:] F^{c(p)} + E[p,:]
// The functions a scene needs (inside the mask, not all zero; each colour channel its own
// function) are clustered by L1 factorization (IRLS fits; the reassignment fits run on an OpenCL
// device or in C++), and each keeps its largest residual entries. The result is what
// relume/container.hpp stores and relume/relight.hpp relights.
//
// One compression run serves every front: compress_file is `relume compress` (plans in memory or
// streamed within the memory budget, checkpoints and resume, rate targets, quantization, the
// container, the errors and the report), compress and compress_with_report run it on a field in
// memory, and Python's relume.compress and relume.compress_file call the same. CompressOptions
// holds every option once, with its default; the command's --help and the Python signature read
// them from here.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <relume/compressed_field.hpp>
#include <relume/container.hpp>
#include <relume/field.hpp>
#include <relume/residual_budget.hpp>
#include <string>

namespace relume {

struct CompressOptions {
  // How the clusters are found: "l1" (the paper's factorization) or "cpca" (clustered PCA, the
  // baseline, into the same container: pca_center, pca_iterations).
  std::string method = "l1";
  std::string pca_center = "none";  // "none" or "mean" (a mean plus terms - 1 components)
  int pca_iterations = 20;          // cpca: cap on fit + reassignment rounds
  // Rounds of least trimmed squares refit for the residual budget after the clustering (-1: none),
  // and whether the refit also clusters by the other method and chooses per cluster.
  int trimmed_refit = -1;
  bool refit_chooses_clusters = false;

  int clusters = 64;                // K
  int terms = 4;                    // t, basis functions per cluster (1 to 16)
  ResidualBudget residual{0, 5.0};  // entries kept per function: a count or a percentage
  // "per-function" (the same count in every function) or "peak" (count x functions over the
  // field, the entries largest relative to their function's peak).
  std::string residual_allocation = "per-function";
  // Field units. A pixel whose every channel is, within noise_floor (RMS over the lights), a
  // multiple of the dark shape has no stored rows (the dark model); 0: every pixel is stored.
  // Negative: 3 x the noise deviation estimated from the field (compress/noise_model.hpp).
  // Residual entries with |value| at or below threshold are dropped; negative: 3 x the estimated
  // deviation (at least the input's quantization step), or noise_floor when one is given.
  float noise_floor = -1.0f;
  float threshold = -1.0f;
  // "irls": the IRLS fits only; "lp-dual", "lp" or "huber": refit every cluster's F and W
  // exactly with that solver after the iterations.
  std::string solver = "irls";
  std::string transform = "identity";  // or "haar": the factorization in a Haar basis
  // Light weighting exponent in [0, 1]: > 0 fits each light's image relative to its own energy
  // (1: fully, 0.5: halfway), so that lights reaching the scene only at grazing angles keep their
  // accuracy; better relit images under concentrated back light, a higher Eq. 16 error. 0: the
  // paper's objective. Identity transform only.
  double light_weighting = 0;
  // "shared": the colour channels of a pixel go to one cluster, so that their errors come from
  // one basis (grey, not coloured; docs/relit_quality.md); "separate": each channel is clustered
  // on its own (the paper's model).
  std::string channel_clusters = "shared";
  int multires = 0;  // levels: cluster a field downsampled 2x per level first
  // Full-resolution iterations after multi-resolution clustering, or a streamed compression's
  // passes over all functions; -1: 2 after multi-resolution, `iterations` streamed.
  int refine = -1;
  int iterations = 4;         // cap on L1 iterations (F-step + reassignment)
  int candidates = 3;         // clusters given the exact L1 fit per function
  int irls_iterations = 5;    // reweighted solves of every IRLS L1 fit
  int min_cluster_size = -1;  // smaller clusters merge away; -1 = max(8, 2 * terms)
  int max_cluster_size = 0;   // larger clusters split; 0 = no limit
  std::uint64_t seed = 1;     // of the cluster seeding
  unsigned threads = 0;       // 0 = all cores
  // Where the reassignment fits run: "opencl" (on `device`, see RelighterOptions::device) or
  // "cpu" (the C++ path).
  std::string assign = "opencl";
  std::string device;

  // How the result is stored (what compress returns is what the container holds): weights and
  // residual "quantized" (integers times the coarsest steps within quantization_budget),
  // "float32" or "float16"; bases "quantized" (8 to 16 bits, a scale per basis row) or "float32".
  std::string weights_precision = "quantized";
  std::string residual_precision = "quantized";
  std::string bases_precision = "quantized";
  // What quantization may add to the squared error of the stored functions, relative. Negative:
  // 0.01 (1%, 0.04 dB), and a rate target tries 0.01, 0.1 and 1 and keeps the best.
  double quantization_budget = -1;
  // With quantized storage: what dropping the basis terms that clusters of dim or simple
  // functions do not need may add to the Eq. 16 error, relative. Negative: 0 (every cluster keeps
  // all terms), and a rate target tries 0 and 0.1 and keeps the better.
  double term_budget = -1;

  // At most one target (0: none). target_error: terms, clusters and per-function residual lengths
  // that reach this relative error (Eq. 16, masked functions) with the fewest bytes. The rate
  // targets choose terms, clusters and residual entries for the lowest error within a container
  // of target_bytes or target_bytes_per_pixel x width x height bytes, or the smallest container
  // whose 8-bit PSNR over target_region ("frame" or "mask") reaches target_psnr dB.
  double target_error = 0;
  std::uint64_t target_bytes = 0;
  double target_bytes_per_pixel = 0;
  double target_psnr = 0;
  std::string target_region = "frame";
  // The models a rate target weighs: "all", "clustered" (the paper's clustered factorization) or
  // "one-basis" (one basis for every function, its weights coded as JPEG 2000 planes).
  std::string target_models = "all";
  double psnr_white = 1.0;          // the field value that is 255 in the report's 8-bit PSNR
  std::filesystem::path psnr_mask;  // the mask of the masked PSNR (default: the field's)

  // Reading the input (compress_file): the object mask (mask_file replaces a folder's mask.png;
  // use_mask false keeps every pixel) and the decoding of 8-bit images: "auto" (float, 16-bit
  // and DiLiGenT folders linear, other 8-bit images sRGB unless they declare linear), "linear" or
  // "srgb".
  std::filesystem::path mask_file;
  bool use_mask = true;
  std::string input_encoding = "auto";
  // The memory the run plans with: a field that does not fit is compressed streamed (read in
  // strips, clustered on a sample). 0: the process's budget (`relume --memory-limit`, else three
  // quarters of the available memory, shared by the MPI ranks on this machine).
  std::uint64_t memory_limit = 0;
  // Continue from OUTPUT.checkpoint (written after every clustering iteration) when it exists.
  bool resume = false;
  // Folder of a streamed compression's scratch file; empty: the output's folder.
  std::filesystem::path scratch;

  bool quiet = true;  // no progress lines on stderr
  // Told (phase, fraction of it done in [0, 1]) at the start and end of each phase and about
  // every 0.1 s in between, on the thread that called, e.g. ("compress: iteration 2, assigning",
  // 0.4). An exception it throws ends the run and propagates: throw Interrupted
  // (relume/error.hpp) to stop it as Ctrl-C would.
  std::function<void(const std::string& phase, double fraction)> progress;
};

// The defaults, for the internal settings that mirror these options.
inline const CompressOptions& compress_defaults() {
  static const CompressOptions defaults;
  return defaults;
}

// What one run made, in the numbers users look at first; `json` is the whole report, as
// `relume compress --report` writes it (times per phase, iterations, bytes per section, errors,
// PSNR, sparseness, memory, the plan and any target's search).
struct CompressionReport {
  std::string input, output;  // output: empty for a run in memory
  std::uint64_t bytes = 0;    // of the container (planned, for a run in memory)
  double bytes_per_pixel = 0;
  double ratio = 0;         // bytes / the float32 field's
  double error_masked = 0;  // Eq. 16 over the stored object's functions
  double error_all = 0;     // over the whole frame (background functions not stored count lost)
  double psnr_frame = 0, psnr_mask = 0;  // 8-bit PSNR (dB)
  int clusters = 0;
  double seconds = 0;
  std::string summary;  // one line for users: bytes, errors, clusters, time
  std::string json;
};

struct CompressionResult {
  CompressedField field;       // as stored (what the container holds)
  ContainerOptions container;  // how write_container stores it, as compress_file would
  CompressionReport report;
};

// Compresses the field folder or .lp file `input` into the container `output` (and writes
// OUTPUT.checkpoint while clustering, removed at the end). Throws Error for bad options (before
// any work), unreadable input or output, Interrupted when an interruption was requested
// (lib/core/interruption.hpp, a Ctrl-C handler, or `progress`).
CompressionReport compress_file(const std::string& input, const std::filesystem::path& output,
                                const CompressOptions& options = {});

// The same run on a field in memory, writing nothing (no checkpoint, no streaming: the field is
// already held).
CompressionResult compress_with_report(const ReflectanceField& field,
                                       const CompressOptions& options = {});
CompressedField compress(const ReflectanceField& field, const CompressOptions& options = {});

}  // namespace relume
