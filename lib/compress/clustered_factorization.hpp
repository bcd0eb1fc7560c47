// Clustered sparse residual factorization of a reflectance field (paper sections 3.3, 3.4, 5):
//   R[p,:] ~ W[p,:] F^{c(p)} + E[p,:]
// The functions a scene needs (inside the mask, not all zero; each colour channel its own
// function) are optionally moved into the Haar basis (paper Eq. 3), scaled to unit norm, clustered
// by L1 factorization (lib/compress/cluster_iterations.hpp, optionally multi-resolution), and their
// residual is cut to the largest entries (lib/compress/residual_selection.hpp). The result is a
// CompressedField. CompressionMethod::cpca clusters by clustered PCA instead
// (lib/compress/clustered_pca.hpp); a trimmed least-squares refit for the residual budget
// (lib/compress/trimmed_refit.hpp) may follow either clustering.
#pragma once

#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <string>
#include <vector>

#include "compress/cluster_iterations.hpp"
#include "compress/clustered_pca.hpp"
#include "compress/multires_clustering.hpp"
#include "compress/residual_selection.hpp"
#include "compress/trimmed_refit.hpp"

namespace relume {

// How the clusters are found: the paper's L1 factorization, or clustered PCA (the baseline).
enum class CompressionMethod : std::uint8_t { l1, cpca };

// "l1" or "cpca"; throws Error naming the bad text.
CompressionMethod parse_compression_method(const std::string& text);
std::string to_string(CompressionMethod method);

struct CompressionOptions {
  CompressionMethod method = CompressionMethod::l1;
  ClusteringOptions clustering;
  ClusteredPcaOptions pca;  // for CompressionMethod::cpca
  // Rounds of the trimmed least-squares refit for the residual budget after the clustering;
  // < 0: none. Skipped when the budget keeps nearly every entry (entries + terms >= lights).
  int trimmed_refit_rounds = -1;
  // Before the refit, also cluster by the other method (L1 or clustered PCA) and choose per
  // cluster between the two clusterings (choose_clusters).
  bool refit_chooses_clusters = false;
  ResidualBudget residual;  // entries kept per function (on average with allocation `peak`)
  ResidualAllocation residual_allocation = ResidualAllocation::per_function;
  // Field units. The noise floor: pixels whose every channel is a multiple of the dark shape
  // within it (RMS over the lights) go to the dark model (PreparedRows, noise_model.hpp).
  // Negative: estimated from the field (estimate_noise). The threshold: residual entries with
  // |value| at or below it are dropped; negative: default_residual_threshold.
  float noise_floor = -1.0f;
  float residual_threshold = -1.0f;
  BasisTransform transform = BasisTransform::identity;
  // > 0: fit R[p,i] / s_i with s_i = (RMS of light i's image / the largest)^light_weighting, so
  // that dim lights' errors count (compress/light_weighting.hpp); at most 1, identity basis only.
  double light_weighting = 0;
  int multires_levels = 0;    // cluster a field downsampled this many times first
  int refine_iterations = 2;  // full-resolution iterations after multi-resolution clustering
};

// The trimmed refit's settings for `entries` residual entries and `rounds` rounds, with the
// candidates, threads and quiet of `clustering` (compress and eval refit alike).
TrimmedRefitOptions trimmed_refit_options(const ClusteringOptions& clustering, int entries,
                                          int rounds);

// A clustering to continue from (a checkpoint): the model and the iterations already done.
struct ClusteringResume {
  ClusterModel model;
  std::vector<IterationRecord> iterations;
};

// Residual thresholds of the sparseness measure (paper Fig. 4d), relative to each function's L2
// norm (which the Haar transform preserves, so both bases are measured alike).
inline constexpr double sparseness_thresholds[] = {1e-3, 1e-2, 5e-2, 1e-1};

struct CompressionStats {
  std::int64_t functions = 0;
  std::int64_t outside_mask = 0;
  std::int64_t all_zero = 0;
  std::size_t stored_rows = 0;
  std::size_t dark_pixels = 0;  // pixels relit by the dark model
  bool one_basis = false;       // the one-basis model (global_basis.hpp) was stored, no clusters
  // A pixel's channels were clustered together (compress/pixel_clusters.hpp); false where each
  // channel was clustered on its own: asked, clustered PCA, the trimmed refit, or a streamed
  // compression.
  bool shared_pixel_clusters = false;
  NoiseModel noise;              // as used
  float residual_threshold = 0;  // as used
  int clusters_asked = 0;
  int clusters = 0;
  int residual_entries = 0;  // per function, from the budget
  std::size_t residual_nonzeros = 0;
  double prepare_seconds = 0, clustering_seconds = 0, residual_seconds = 0;
  ClusteringTrace clustering;
  std::optional<MultiresTrace> multires;
  std::optional<TrimmedRefitTrace> trimmed_refit;
  // Fraction of the full residual's entries with |e| <= threshold * ||R[p,:]||_2.
  std::vector<double> sparseness;
};

// Throws Error naming the first option out of range (terms, clusters, candidates, iterations,
// levels, threshold, size limits, threads): what compress_field checks before any work, minus what
// needs the field (terms below its lights).
void validate_compression_options(const CompressionOptions& options);

// The clustering of `rows` (a field's prepared rows, or a streamed compression's sample of them,
// of `lights` lights) by options.method, multi-resolution aside: continued from `resume` when
// given (L1 only; Error when its model does not match the rows), else seeded. Adds to
// stats.clustering.
ClusterModel cluster_prepared_rows(const WorkingRows& rows, int lights,
                                   const CompressionOptions& options, CompressionStats& stats,
                                   const IterationHook& hook = {},
                                   const ClusteringResume* resume = nullptr);

// `hook` runs after every clustering iteration (for checkpoints); `resume` skips the seeding (and
// the multi-resolution start) and continues its iterations up to the cap.
CompressedField compress_field(const ReflectanceField& field, const CompressionOptions& options,
                               CompressionStats& stats, const IterationHook& hook = {},
                               const ClusteringResume* resume = nullptr);

// A field's rows as compress_field prepares them for clustering (its noise model, dark pixels and
// light weighting by the options): the same for any terms, clusters and residual budget, so a
// search over those prepares once (compress_prepared_field).
struct PreparedField {
  NoiseModel noise;
  PreparedRows rows;
  double seconds = 0;  // how long preparing took
};
PreparedField prepare_field(const ReflectanceField& field, const CompressionOptions& options);
// The same with the noise model made already (noise_model_for(field, options)).
PreparedField prepare_field(const ReflectanceField& field, const CompressionOptions& options,
                            NoiseModel noise);

// The noise model a compression with `options` uses: the user's noise floor, else the estimate.
NoiseModel noise_model_for(const ReflectanceField& field, const CompressionOptions& options);

// compress_field with the rows `prepared` by prepare_field(field, O) for options O that differ
// from `options` at most in terms, clusters and the residual budget.
CompressedField compress_prepared_field(const ReflectanceField& field,
                                        const PreparedField& prepared,
                                        const CompressionOptions& options, CompressionStats& stats,
                                        const IterationHook& hook = {},
                                        const ClusteringResume* resume = nullptr);

// The field of `prepared` with a model of no terms in one cluster and no residual: what every
// (terms, clusters) pair stores alike, its stored functions, dark pixels and dark model. For
// bounds on what no pair's model can change (psnr_8bit_of_unstored).
CompressedField zero_model_field(const ReflectanceField& field, const PreparedField& prepared,
                                 BasisTransform transform);

// Builds the CompressedField of `field` from a finished clustering of its prepared rows: W and E
// scaled back to the field's units, E cut by `residual_entries` (all rows alike) or by
// `entries_per_row` when not empty. Fills the residual and sparseness fields of `stats`.
CompressedField build_compressed_field(const ReflectanceField& field, const PreparedRows& prepared,
                                       const ClusterModel& model, BasisTransform transform,
                                       int residual_entries, float residual_threshold,
                                       const std::vector<int>& entries_per_row,
                                       CompressionStats& stats, unsigned threads);

}  // namespace relume
