// Implementation of clustered sparse residual factorization of a field
// (see clustered_factorization.hpp).
#include "compress/clustered_factorization.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <relume/error.hpp>

#include "compress/light_weighting.hpp"
#include "compress/peak_residual_allocation.hpp"
#include "core/elapsed_time.hpp"
#include "core/parallel.hpp"
#include "core/value_scans.hpp"
#include "model/haar_transform.hpp"

namespace relume {
namespace {

void validate_options(const ReflectanceField& field, const CompressionOptions& options) {
  validate_compression_options(options);
  if (options.clustering.terms >= field.lights())
    throw Error("terms per cluster (" + std::to_string(options.clustering.terms) +
                ") must be fewer than the lights (" + std::to_string(field.lights()) + ")");
}

}  // namespace

void validate_compression_options(const CompressionOptions& options) {
  const ClusteringOptions& clustering = options.clustering;
  if (clustering.terms < 1 || clustering.terms > max_cluster_terms)
    throw Error("terms per cluster must be in [1, " + std::to_string(max_cluster_terms) +
                "], got " + std::to_string(clustering.terms));
  if (clustering.clusters < 1)
    throw Error("clusters must be >= 1, got " + std::to_string(clustering.clusters));
  if (clustering.candidates < 1)
    throw Error("candidate clusters per function must be >= 1, got " +
                std::to_string(clustering.candidates));
  if (clustering.max_iterations < 0 || options.refine_iterations < 0)
    throw Error("iteration counts must be >= 0");
  if (options.multires_levels < 0 || options.multires_levels > 8)
    throw Error("multi-resolution levels must be in [0, 8], got " +
                std::to_string(options.multires_levels));
  if (std::isnan(options.residual_threshold) || !std::isfinite(options.residual_threshold))
    throw Error("residual threshold must be a finite value (negative: the noise floor), got " +
                std::to_string(options.residual_threshold));
  if (std::isnan(options.noise_floor) || !std::isfinite(options.noise_floor))
    throw Error("noise floor must be a finite value (negative: estimated from the field), got " +
                std::to_string(options.noise_floor));
  if (!(options.light_weighting >= 0 && options.light_weighting <= 1))
    throw Error("the light weighting must be an exponent in [0, 1], got " +
                std::to_string(options.light_weighting));
  if (options.light_weighting > 0 && options.transform != BasisTransform::identity)
    throw Error(
        "light weighting scales the lights, which the Haar transform mixes: use one of "
        "--light-weighting and --transform haar");
  validate_size_limits(clustering.sizes, clustering.terms);
  resolve_thread_count(clustering.threads);
  if (options.method == CompressionMethod::cpca &&
      (options.multires_levels > 0 || clustering.exact_refit))
    throw Error(
        "clustered PCA (--method cpca) has no multi-resolution start and no exact L1 "
        "refit; leave --multires and --solver at their defaults");
  if (options.refit_chooses_clusters && options.trimmed_refit_rounds < 0)
    throw Error("choosing clusters for the refit needs the trimmed refit (--trimmed-refit N)");
}

namespace {

// The trimmed least-squares refit for the residual budget, after choosing per cluster between
// the method's clustering and the other method's when asked.
void refit_for_budget(const WorkingRows& rows, const CompressionOptions& options,
                      CompressionStats& stats, ClusterModel& model) {
  const ClusteringOptions& clustering = options.clustering;
  const TrimmedRefitOptions refit =
      trimmed_refit_options(clustering, stats.residual_entries, options.trimmed_refit_rounds);
  TrimmedRefitTrace& trace = stats.trimmed_refit.emplace();
  if (options.refit_chooses_clusters) {
    ClusteringTrace other_trace;
    const ClusterModel other = options.method == CompressionMethod::cpca
                                   ? cluster_rows(rows, clustering, other_trace)
                                   : cluster_rows_pca(rows, clustering, options.pca, other_trace);
    const std::vector<double> own = trimmed_errors(rows, model, refit.entries, refit.threads);
    trace.objective_before_choice = std::accumulate(own.begin(), own.end(), 0.0);
    double chosen = 0;
    model = choose_clusters(rows, model, other, refit, chosen);
  }
  refit_trimmed_least_squares(rows, model, refit, trace);
}

}  // namespace

TrimmedRefitOptions trimmed_refit_options(const ClusteringOptions& clustering, int entries,
                                          int rounds) {
  TrimmedRefitOptions refit;
  refit.entries = entries;
  refit.rounds = rounds;
  refit.candidates = clustering.candidates;
  refit.threads = clustering.threads;
  refit.quiet = clustering.quiet;
  return refit;
}

CompressionMethod parse_compression_method(const std::string& text) {
  if (text == "l1") return CompressionMethod::l1;
  if (text == "cpca") return CompressionMethod::cpca;
  throw Error("compression method must be 'l1' or 'cpca', got '" + text + "'");
}

std::string to_string(CompressionMethod method) {
  return method == CompressionMethod::cpca ? "cpca" : "l1";
}

namespace {

// What a compressed field of `prepared` holds whatever its model: its shape, mask, lights, stored
// functions and dark model; `terms` and `clusters` say the model's size, which is not filled.
CompressedField field_of_prepared_rows(const ReflectanceField& field, const PreparedRows& prepared,
                                       BasisTransform transform, int terms, int clusters) {
  CompressedField out;
  out.width = field.width;
  out.height = field.height;
  out.channels = field.channels;
  out.lights = field.lights();
  out.terms = terms;
  out.clusters = clusters;
  out.transform = transform;
  out.mask = field.mask.empty() ? std::vector<std::uint8_t>(field.pixels(), 1) : field.mask;
  for (auto& inside : out.mask) inside = inside != 0;
  out.directions = field.directions;
  out.intensities = field.intensities;
  out.stored_function = prepared.functions;
  out.dark_pixels = prepared.dark_pixels;
  out.dark = prepared.dark;
  out.dark_gains = prepared.dark_gains;
  out.dark_gain_step = prepared.dark_gain_step;
  out.non_negative = all_non_negative(field.values.data(), std::size_t(field.values.size()));
  return out;
}

}  // namespace

CompressedField build_compressed_field(const ReflectanceField& field, const PreparedRows& prepared,
                                       const ClusterModel& model, BasisTransform transform,
                                       int residual_entries, float residual_threshold,
                                       const std::vector<int>& entries_per_row,
                                       CompressionStats& stats, unsigned threads) {
  const int lights = field.lights(), terms = model.terms;
  const std::size_t rows = prepared.functions.size();
  CompressedField out = field_of_prepared_rows(field, prepared, transform, terms, model.clusters);
  out.cluster.assign(model.assignment.begin(), model.assignment.end());
  // The model fits the weighted rows R / S: F S is the basis of R (light_weighting.hpp).
  const std::vector<float>& light_scale = prepared.light_scale;
  out.bases = model.bases;
  if (!light_scale.empty())
    for (std::size_t v = 0; v < out.bases.size(); ++v) out.bases[v] *= light_scale[v % lights];
  out.weights.resize(static_cast<Eigen::Index>(rows), terms);

  // Residual rows are built in blocks in parallel, then concatenated in order.
  constexpr std::size_t block = 2048;
  const std::size_t blocks = (rows + block - 1) / block;
  std::vector<ResidualRows> parts(blocks);
  constexpr std::size_t levels = std::size(sparseness_thresholds);
  std::vector<std::array<std::size_t, levels>> sparse_counts(blocks);
  parallel_for(blocks, threads, [&](std::size_t b, unsigned) {
    std::vector<float> row(lights);
    std::vector<int> scratch;
    ResidualRows& part = parts[b];
    part.row_offsets.push_back(0);
    sparse_counts[b].fill(0);
    for (std::size_t r = b * block; r < std::min(rows, (b + 1) * block); ++r) {
      const auto original = field.values.row(prepared.functions[r]);
      std::copy(original.data(), original.data() + lights, row.begin());
      for (std::size_t i = 0; i < light_scale.size(); ++i) row[i] /= light_scale[i];
      if (transform == BasisTransform::haar) haar_forward(row.data(), lights, 1);
      const float norm = prepared.rows.norms[r];
      float* weights = out.weights.row(static_cast<Eigen::Index>(r)).data();
      for (int j = 0; j < terms; ++j)
        weights[j] = model.weights(static_cast<Eigen::Index>(r), j) * norm;
      const float* basis = model.basis(model.assignment[r]);
      for (int i = 0; i < lights; ++i) {
        double value = row[i];
        for (int j = 0; j < terms; ++j)
          value -= double(weights[j]) * basis[std::size_t(j) * lights + i];
        row[i] = static_cast<float>(value);
        for (std::size_t level = 0; level < levels; ++level)
          sparse_counts[b][level] += std::fabs(value) <= sparseness_thresholds[level] * norm;
      }
      const int kept = entries_per_row.empty() ? residual_entries : entries_per_row[r];
      if (light_scale.empty()) {
        append_residual_row(row.data(), lights, kept, residual_threshold, part, scratch);
        continue;
      }
      // Weighted: the largest entries of R / S - W F, the threshold still in field units.
      for (int i = 0; i < lights; ++i)
        if (std::fabs(row[i]) * light_scale[i] <= residual_threshold) row[i] = 0;
      const std::size_t begin = part.values.size();
      append_residual_row(row.data(), lights, kept, 0.0f, part, scratch);
      unweight_residual_row(part, begin, light_scale);
    }
  });
  out.residual.row_offsets.reserve(rows + 1);
  out.residual.row_offsets.push_back(0);
  for (const ResidualRows& part : parts) {
    const std::uint32_t base = out.residual.row_offsets.back();
    for (std::size_t r = 1; r < part.row_offsets.size(); ++r)
      out.residual.row_offsets.push_back(base + part.row_offsets[r]);
    out.residual.light_index.insert(out.residual.light_index.end(), part.light_index.begin(),
                                    part.light_index.end());
    out.residual.values.insert(out.residual.values.end(), part.values.begin(), part.values.end());
  }
  stats.residual_nonzeros = out.residual.nonzeros();
  stats.sparseness.assign(levels, 0.0);
  for (std::size_t level = 0; level < levels; ++level) {
    std::size_t count = 0;
    for (const auto& counts : sparse_counts) count += counts[level];
    stats.sparseness[level] = rows == 0 ? 0.0 : double(count) / (double(rows) * lights);
  }
  return out;
}

CompressedField zero_model_field(const ReflectanceField& field, const PreparedField& prepared,
                                 BasisTransform transform) {
  CompressedField out = field_of_prepared_rows(field, prepared.rows, transform, 0, 1);
  out.cluster.assign(out.stored_function.size(), 0);
  out.weights.resize(Eigen::Index(out.stored_function.size()), 0);
  out.residual.row_offsets.assign(out.stored_function.size() + 1, 0);
  return out;
}

ClusterModel cluster_prepared_rows(const WorkingRows& rows, int lights,
                                   const CompressionOptions& options, CompressionStats& stats,
                                   const IterationHook& hook, const ClusteringResume* resume) {
  const ClusteringOptions& clustering = options.clustering;
  ClusterModel model;
  if (rows.rows() == 0) {
    model.terms = clustering.terms;
    model.lights = lights;
  } else if (resume && options.method == CompressionMethod::cpca) {
    throw Error("clustered PCA (--method cpca) writes no checkpoints and cannot resume one");
  } else if (resume) {
    model = resume->model;
    if (model.terms != clustering.terms || model.lights != lights ||
        model.assignment.size() != rows.rows())
      throw Error("the checkpoint does not match this input and these settings (" +
                  std::to_string(model.assignment.size()) + " rows, " +
                  std::to_string(model.terms) + " terms, " + std::to_string(model.lights) +
                  " lights; expected " + std::to_string(rows.rows()) + ", " +
                  std::to_string(clustering.terms) + ", " + std::to_string(lights) + ")");
    stats.clustering.iterations = resume->iterations;
    int done = 0;
    for (const auto& record : resume->iterations) done += record.iteration > 0;
    const int cap =
        options.multires_levels > 0 ? options.refine_iterations : clustering.max_iterations;
    // A checkpoint written after the iteration that settled is the last one: the uninterrupted
    // run stopped there, so the resumed one iterates no more (else it would write another model).
    const bool settled = options.multires_levels == 0 && done > 0 &&
                         double(resume->iterations.back().changed) <=
                             clustering.settle_fraction * double(rows.rows());
    iterate_clusters(rows, model, clustering, settled ? 0 : std::max(0, cap - done),
                     stats.clustering, hook);
    if (settled) stats.clustering.settled = true;
  } else if (options.method == CompressionMethod::cpca) {
    model = cluster_rows_pca(rows, clustering, options.pca, stats.clustering);
  } else {
    model = cluster_rows(rows, clustering, stats.clustering, hook);
  }
  return model;
}

NoiseModel noise_model_for(const ReflectanceField& field, const CompressionOptions& options) {
  return options.noise_floor >= 0 ? noise_floor_model(field, options.noise_floor)
                                  : estimate_noise(field, options.clustering.threads);
}

PreparedField prepare_field(const ReflectanceField& field, const CompressionOptions& options) {
  validate_compression_options(options);
  const auto start = Clock::now();
  PreparedField prepared = prepare_field(field, options, noise_model_for(field, options));
  prepared.seconds = seconds_since(start);
  return prepared;
}

PreparedField prepare_field(const ReflectanceField& field, const CompressionOptions& options,
                            NoiseModel noise) {
  validate_compression_options(options);
  const auto start = Clock::now();
  PreparedField prepared;
  prepared.noise = std::move(noise);
  prepared.rows = prepare_rows(
      field, options.transform == BasisTransform::haar, prepared.noise, options.clustering.threads,
      options.light_weighting > 0 ? light_weighting_scales(field, options.light_weighting)
                                  : std::vector<float>{});
  prepared.seconds = seconds_since(start);
  return prepared;
}

CompressedField compress_field(const ReflectanceField& field, const CompressionOptions& options,
                               CompressionStats& stats, const IterationHook& hook,
                               const ClusteringResume* resume) {
  validate_options(field, options);
  return compress_prepared_field(field, prepare_field(field, options), options, stats, hook,
                                 resume);
}

CompressedField compress_prepared_field(const ReflectanceField& field,
                                        const PreparedField& prepared_field,
                                        const CompressionOptions& options, CompressionStats& stats,
                                        const IterationHook& hook, const ClusteringResume* resume) {
  validate_options(field, options);
  const ClusteringOptions& clustering = options.clustering;
  const bool haar = options.transform == BasisTransform::haar;
  const PreparedRows& prepared = prepared_field.rows;
  stats.noise = prepared_field.noise;
  stats.residual_threshold = options.residual_threshold >= 0
                                 ? options.residual_threshold
                                 : default_residual_threshold(stats.noise, field);
  stats.functions = field.functions();
  stats.stored_rows = prepared.functions.size();
  stats.dark_pixels = prepared.dark_pixels.size();
  if (!field.mask.empty()) {
    for (const auto inside : field.mask) stats.outside_mask += (inside == 0) * field.channels;
  }
  stats.all_zero = stats.functions - stats.outside_mask - std::int64_t(stats.stored_rows) -
                   std::int64_t(stats.dark_pixels) * field.channels;
  stats.clusters_asked = clustering.clusters;
  stats.prepare_seconds = prepared_field.seconds;

  auto start = Clock::now();
  ClusterModel model;
  if (options.multires_levels > 0 && !prepared.functions.empty() && !resume) {
    stats.multires.emplace();
    model = multires_start(field, prepared, options.multires_levels, haar, stats.noise, clustering,
                           *stats.multires);
    iterate_clusters(prepared.rows, model, clustering, options.refine_iterations, stats.clustering,
                     hook);
  } else {
    model = cluster_prepared_rows(prepared.rows, field.lights(), options, stats, hook, resume);
  }
  stats.residual_entries = options.residual.entries_for(field.lights());
  const bool refit = options.trimmed_refit_rounds >= 0 && !prepared.functions.empty() &&
                     stats.residual_entries + model.terms < model.lights;
  if (refit) refit_for_budget(prepared.rows, options, stats, model);
  // The trimmed refit reassigns each row on its own.
  stats.shared_pixel_clusters =
      options.method == CompressionMethod::l1 && clustering.shared_pixel_clusters && !refit;
  stats.clusters = model.clusters;
  stats.clustering_seconds = seconds_since(start);

  start = Clock::now();
  const bool by_peak = options.residual_allocation == ResidualAllocation::peak;
  // By peak, a function may take up to peak_allocation_row_cap times the average budget.
  const int row_cap =
      by_peak ? std::min(field.lights(), stats.residual_entries * peak_allocation_row_cap)
              : stats.residual_entries;
  CompressedField out =
      build_compressed_field(field, prepared, model, options.transform, row_cap,
                             stats.residual_threshold, {}, stats, clustering.threads);
  if (by_peak) {
    std::vector<double> peak(out.stored_rows());
    for (std::size_t r = 0; r < peak.size(); ++r)
      peak[r] = field.values.row(out.stored_function[r]).cwiseAbs().maxCoeff();
    keep_largest_relative_to_peak(out.residual, peak,
                                  std::size_t(stats.residual_entries) * out.stored_rows());
    stats.residual_nonzeros = out.residual.nonzeros();
  }
  stats.residual_seconds = seconds_since(start);
  return out;
}

}  // namespace relume
