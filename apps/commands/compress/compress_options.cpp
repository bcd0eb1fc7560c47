// The options of `relume compress` bound to CompressOptions, in groups: what is stored, how the
// clusters are found, how it is stored, the targets, and the run.
#include "commands/compress/compress_options.hpp"

#include "options/finite_numbers.hpp"

namespace relume {
namespace {

void add_method_options(CLI::App& command, CompressArguments& arguments) {
  CompressOptions& options = arguments.options;
  command.add_option("--method", options.method,
                     "l1: the paper's clustered sparse residual factorization (default); "
                     "cpca: clustered PCA (Sloan et al. 2003), the baseline, into the same "
                     "container (--pca-center, --pca-iterations)");
  command.add_option("--pca-center", options.pca_center,
                     "cpca: none (default: --terms components per cluster, the stronger "
                     "at equal bytes) or mean (a mean plus --terms - 1 components, stored "
                     "as their span: Sloan et al.'s mean + t components is --pca-center "
                     "mean --terms t+1)");
  command
      .add_option("--pca-iterations", options.pca_iterations,
                  "cpca: cap on fit + reassignment rounds (they stop once settled)")
      ->capture_default_str();
  command.add_option(
      "--trimmed-refit", options.trimmed_refit,
      "Rounds of least trimmed squares refit for the --residual budget after the clustering "
      "(-1: none): lowers the error with that many residual entries (it may raise it at "
      "shorter caps of the dynamic residual), e.g. --residual 0 --trimmed-refit 2");
  command.add_flag(
      "--refit-chooses-clusters", options.refit_chooses_clusters,
      "With --trimmed-refit: also cluster by the other method (cpca for l1, l1 for cpca) and "
      "choose per cluster between the two before the refit (slower; never worse than either "
      "at the budget)");
  command.add_option("--clusters", options.clusters, "Clusters K")->capture_default_str();
  command.add_option("--terms", options.terms, "Basis functions per cluster t (1 to 16)")
      ->capture_default_str();
  command
      .add_option("--residual", arguments.residual,
                  "Residual entries kept per function: a count N or a percentage of the "
                  "lights P%")
      ->capture_default_str();
  command
      .add_option("--residual-allocation", options.residual_allocation,
                  "How the residual entries are spread: per-function (default: the same N "
                  "in every function) or peak (N x functions over the field, the entries "
                  "largest relative to their function's peak: bounds the largest per-light "
                  "error, which a concentrated light such as a sun shows; a function keeps "
                  "at most 4N). Example: --residual 12 --residual-allocation peak")
      ->check(CLI::IsMember({"per-function", "peak"}));
  command.add_option("--noise-floor", options.noise_floor,
                     "Field units: a pixel whose every channel is, within X (RMS over the "
                     "lights), a multiple of the dark shape (the mean of the darkest pixels) "
                     "has no stored rows and relights as that multiple; 0 stores every pixel. "
                     "Default: 3 x the camera noise estimated from the images themselves "
                     "(reported in the summary and the report). Example: --noise-floor 0");
  command.add_option("--threshold", options.threshold,
                     "Drop residual entries with |value| <= X, in field units (default: 3 x the "
                     "estimated noise deviation, at least the input's quantization step; the "
                     "noise floor when one is given)");
  command.add_option("--transform", options.transform,
                     "Basis of the factorization: identity (default) or haar (orthonormal Haar "
                     "wavelet over the light order; the residual is sparse in that basis)");
  command
      .add_option(
          "--light-weighting", options.light_weighting,
          "Fit each light's image relative to its own energy, as an exponent in [0, 1]: 1 "
          "fully, 0.5 halfway, 0 not at all (the paper's Eq. 16). Lights that reach the "
          "object only at grazing angles (a sun behind it) then keep their accuracy: better "
          "relit images under concentrated or back light, a higher Eq. 16 error and lower "
          "average PSNR (docs/relit_quality.md); e.g. --light-weighting 0.5")
      ->capture_default_str();
}

void add_clustering_options(CLI::App& command, CompressOptions& options) {
  command.add_option("--solver", options.solver,
                     "irls: the fast IRLS L1 fits only (default); lp-dual, lp or huber: refit "
                     "every cluster's F and W exactly with that solver after the iterations");
  command
      .add_option("--channel-clusters", options.channel_clusters,
                  "shared: a pixel's colour channels go to one cluster, so that their errors "
                  "come from one basis and show grey rather than as coloured specks (default); "
                  "separate: each channel is clustered on its own, as in the paper")
      ->check(CLI::IsMember({"shared", "separate"}))
      ->capture_default_str();
  command.add_option("--multires", options.multires,
                     "Cluster a field downsampled 2x per level first, then assign full-resolution "
                     "functions among the clusters near them (default 0: off)");
  command.add_option("--refine", options.refine,
                     "Full-resolution iterations after --multires clustering (default 2), or "
                     "a streamed compression's passes over all functions after the sample's "
                     "clustering (default: --iterations)");
  command
      .add_option("--iterations", options.iterations,
                  "Cap on L1 iterations (F-step + reassignment); they stop earlier once "
                  "fewer than 0.2% of the functions change cluster")
      ->capture_default_str();
  command
      .add_option("--candidates", options.candidates,
                  "Clusters given the exact L1 fit per function, chosen by the smallest "
                  "least-squares projection error")
      ->capture_default_str();
  command
      .add_option("--irls-iterations", options.irls_iterations,
                  "Reweighted solves of every IRLS L1 fit (weights and bases)")
      ->capture_default_str();
  command.add_option("--min-cluster-size", options.min_cluster_size,
                     "Clusters with fewer functions merge into their second-best cluster "
                     "(default max(8, 2 x terms))");
  command.add_option("--max-cluster-size", options.max_cluster_size,
                     "Clusters with more functions split into two halves (default 0: no limit)");
  command.add_option("--seed", options.seed, "Random seed of the cluster seeding")
      ->capture_default_str();
  command.add_option("--threads", options.threads,
                     "Worker threads, also of PoCL for --assign opencl unless "
                     "POCL_MAX_PTHREAD_COUNT is set (default 0: all cores)");
  command.add_option("--assign", options.assign,
                     "Where the reassignment fits run: opencl (default: kernels/assign.cl on "
                     "--device) or cpu (the C++ reference path)");
  command.add_option("--device", options.device,
                     "OpenCL device for --assign opencl: a substring of 'platform / device' "
                     "(default RELUME_DEVICE, else the first GPU, else PoCL)");
}

void add_storage_options(CLI::App& command, CompressOptions& options) {
  command.add_option("--weights-precision", options.weights_precision,
                     "Stored W: quantized (default: integers times one step, the coarsest "
                     "within --quantization-budget), float32 or float16");
  command.add_option("--residual-precision", options.residual_precision,
                     "Stored residual values: quantized (default), float32 or float16");
  command.add_option("--bases-precision", options.bases_precision,
                     "Stored bases: quantized (default: 8 to 16 bits per value with a "
                     "scale per basis function) or float32");
  command
      .add_option("--quantization-budget", options.quantization_budget,
                  "How much quantization may add to the squared error of the stored "
                  "functions, relative (0.01: 1%, 0.04 dB). Default 0.01; a rate target "
                  "(--target-bytes, --target-psnr) tries 0.01, 0.1 and 1 and keeps the best: "
                  "coarser steps are the first way to fewer bytes");
  command.add_option(
      "--term-budget", options.term_budget,
      "With quantized storage, how much dropping the basis terms that clusters of dim or "
      "simple functions do not need may add to the error (Eq. 16), relative: the terms that "
      "cost the most bytes per error go first. Default 0 (every cluster keeps all --terms); "
      "a rate target (--target-bytes, --target-psnr) tries 0 and 0.1 and keeps the better. "
      "Pays on noisy whole frames (docs/compression.md, 'Terms per cluster')");
}

void add_target_options(CLI::App& command, CompressOptions& options) {
  command.add_option("--target-error", options.target_error,
                     "Choose terms, clusters and per-function residual lengths that reach this "
                     "relative error (paper Eq. 16, masked functions) with the fewest bytes")
      ->check(positive_number());
  command.add_option("--target-bytes", options.target_bytes,
                     "Rate control: choose terms, clusters and the residual entries kept "
                     "for the lowest error (Eq. 16) in a container of at most N bytes; the "
                     "report's rate_target lists every point tried")
      ->check(positive_number());
  command.add_option("--target-bytes-per-pixel", options.target_bytes_per_pixel,
                     "Rate control as --target-bytes, for B bytes per pixel of the frame "
                     "(B x width x height bytes), e.g. 0.5")
      ->check(positive_number());
  command.add_option("--target-psnr", options.target_psnr,
                     "Rate control: the smallest container whose 8-bit PSNR (dB, over "
                     "--target-region; --psnr-white) reaches DB, e.g. 40")
      ->check(positive_number());
  command
      .add_option("--target-region", options.target_region,
                  "Where --target-psnr is measured: frame (every pixel) or mask (inside "
                  "--psnr-mask, else the field's mask)")
      ->check(CLI::IsMember({"frame", "mask"}))
      ->capture_default_str();
  command
      .add_option("--target-models", options.target_models,
                  "Which models a rate target weighs: all (the best wins), clustered (the "
                  "paper's clusters: few terms per pixel, the fastest relighting) or one-basis "
                  "(one basis for every function, its weights coded as JPEG 2000 images: the "
                  "fewest bytes at low and middle rates)")
      ->check(CLI::IsMember({"all", "clustered", "one-basis"}))
      ->capture_default_str();
  command
      .add_option("--psnr-white", options.psnr_white,
                  "The field value that is 255 in the report's 8-bit PSNR (1 for fields of "
                  "8-bit or normalised images)")
      ->capture_default_str();
  command.add_option("--psnr-mask", options.psnr_mask,
                     "A mask image (non-zero = inside) for the report's masked PSNR and "
                     "--target-region mask, e.g. the object's mask when the whole frame "
                     "is compressed (default: the field's mask)");
}

void add_run_options(CLI::App& command, CompressArguments& arguments) {
  command.add_option("--report", arguments.report,
                     "Write a JSON report (times, iterations, bytes, errors, sparseness, memory)");
  command.add_flag("--resume", arguments.options.resume,
                   "Continue from OUT.checkpoint, written after every clustering iteration "
                   "(of the sample's clustering when the plan is streamed)");
  command.add_option(
      "--scratch", arguments.options.scratch,
      "Folder of the scratch file a streamed compression keeps its rows in (float16, up to "
      "functions x lights x 2 bytes; removed at the end, on error and on Ctrl-C). Default: "
      "the output's folder. A field that does not fit --memory-limit (a global option; "
      "default three quarters of the available memory) is compressed streamed: read in "
      "strips, clustered on a sample, refined and built in passes over the strips; the "
      "plan is printed and is in the report");
  add_field_input_options(command, arguments.field_input);
}

}  // namespace

void add_compress_options(CLI::App& command, CompressArguments& arguments) {
  command.add_option("inputs", arguments.inputs, "Field folders or .lp files")->required();
  command
      .add_option("-o,--output", arguments.output,
                  "Output .relume file; with several inputs, a folder that receives one "
                  "<input name>.relume per input")
      ->required();
  add_method_options(command, arguments);
  add_clustering_options(command, arguments.options);
  add_storage_options(command, arguments.options);
  add_target_options(command, arguments.options);
  add_run_options(command, arguments);
}

CompressOptions compress_options(const CompressArguments& arguments) {
  CompressOptions options = arguments.options;
  options.residual = ResidualBudget::parse(arguments.residual);
  options.mask_file = arguments.field_input.mask_file;
  options.use_mask = !arguments.field_input.no_mask;
  options.input_encoding = requested_encoding(arguments.field_input);
  return options;
}

}  // namespace relume
