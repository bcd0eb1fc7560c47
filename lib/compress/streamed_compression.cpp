// Implementation of streamed compression (see streamed_compression.hpp).
// Interruptible: every strip and block checks for a Ctrl-C (lib/core/interruption.hpp).
#include "compress/streamed_compression.hpp"

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <relume/error.hpp>

#include "compress/cluster_basis.hpp"
#include "compress/compressed_strip_file.hpp"
#include "compress/peak_residual_allocation.hpp"
#include "compress/rank_exchange.hpp"
#include "compress/scratch_rows.hpp"
#include "core/elapsed_time.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/ranks.hpp"
#include "model/compressed_field_rows.hpp"
#include "model/haar_transform.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

// Every row of `rows` assigned to its best cluster of `bases` (a model without assignment),
// among the candidates nearest by least squares and, when `current` is not empty, the row's
// current cluster (as the in-memory iterations keep it among the candidates), with its weights
// refitted.
AssignmentResult assign_to_bases(const WorkingRows& rows, const ClusterModel& bases,
                                 const ClusteringOptions& options,
                                 const std::vector<std::int32_t>& current) {
  CandidateOptions candidate_options;
  candidate_options.count = options.candidates;
  if (!current.empty()) candidate_options.always_include = &current;
  const CandidateLists candidates =
      nearest_subspace_candidates(rows, bases, candidate_options, options.threads);
  if (options.assign) return options.assign(rows, bases, candidates);
  return assign_to_best_cluster(rows, bases, candidates, options.weight_fit, options.threads);
}

// What pass 1 keeps of this rank's rows besides the scratch rows.
struct ReadResult {
  std::vector<std::uint64_t> stored_per_row;  // stored functions of every pixel row read
  std::size_t dark_pixels = 0;
  std::int64_t outside_mask = 0;  // functions
};

// Pixel rows [begin_row, end_row): this rank's share of the field.
ReadResult read_strips(FieldStripReader& reader, const CompressionOptions& options,
                       const CompressionPlan& plan, const NoiseModel& noise, int begin_row,
                       int end_row, ScratchRows& scratch) {
  const ReflectanceField& header = reader.header();
  const std::size_t row_functions = std::size_t(header.width) * std::size_t(header.channels);
  ReadResult result;
  result.stored_per_row.assign(std::size_t(end_row - begin_row), 0);
  ProgressReporter progress("compress: reading strips", std::uint64_t(end_row - begin_row),
                            options.clustering.quiet);
  reader.rewind();
  for (int y = begin_row; y < end_row; y += plan.strip_rows) {
    throw_if_interrupted();
    const int rows = std::min(plan.strip_rows, end_row - y);
    const ReflectanceField strip = reader.read(y, rows);
    const PreparedRows prepared = prepare_rows(strip, options.transform == BasisTransform::haar,
                                               noise, options.clustering.threads);
    for (const std::uint32_t function : prepared.functions)
      ++result.stored_per_row[std::size_t(y - begin_row) + function / row_functions];
    result.dark_pixels += prepared.dark_pixels.size();
    for (const std::uint8_t inside : strip.mask)
      result.outside_mask += (inside == 0) * header.channels;
    scratch.append(prepared.rows);
    progress.advance(std::uint64_t(rows));
  }
  progress.finish();
  return result;
}

// Every `stride`-th row of the field's stored functions (a spatially stratified sample), as the
// scratch rows hold them: this rank's rows are the field's from `first_row` on.
WorkingRows sample_rows(const ScratchRows& scratch, std::uint64_t first_row, std::size_t stride) {
  std::vector<float> values, norms;
  for (std::size_t r = std::size_t((stride - first_row % stride) % stride); r < scratch.rows();
       r += stride) {
    const WorkingRows row = scratch.read(r, 1);
    values.insert(values.end(), row.values.data(), row.values.data() + row.lights());
    norms.push_back(row.norms[0]);
  }
  WorkingRows sample;
  sample.values = Eigen::Map<RowMatrixF>(values.data(), Eigen::Index(norms.size()),
                                         Eigen::Index(scratch.lights()));
  sample.norms = std::move(norms);
  return sample;
}

// One refinement pass over this rank's scratch rows, as an in-memory iteration: every row
// assigned to its best cluster (its weights refitted into `weights`), then every cluster's
// F-step by IRLS, each round a pass over the rows whose sums the root adds up over the ranks and
// solves (deterministic: each cluster's rows are added in row order by one thread, and the ranks'
// sums in rank order). `assignment` holds every row's cluster of the previous pass (empty before
// the first). The record's objective and changed rows are over all ranks.
StreamedPass refine_pass(Ranks& ranks, const ScratchRows& scratch, std::size_t block_rows,
                         const ClusteringOptions& options, ClusterModel& bases,
                         std::vector<std::int32_t>& assignment, RowMatrixF& weights, int pass) {
  const auto start = Clock::now();
  StreamedPass record;
  record.pass = pass;
  const bool first = assignment.empty();
  assignment.resize(scratch.rows(), -1);
  weights.resize(Eigen::Index(scratch.rows()), bases.terms);
  const int rounds = options.basis_fit.iterations;
  ProgressReporter progress("compress: refinement pass " + std::to_string(pass),
                            scratch.rows() * std::uint64_t(rounds + 2), options.quiet);
  double totals[2] = {0, 0};  // L1 residual, changed rows
  for (std::size_t first_row = 0; first_row < scratch.rows(); first_row += block_rows) {
    throw_if_interrupted();
    const std::size_t count = std::min(block_rows, scratch.rows() - first_row);
    const WorkingRows rows = scratch.read(first_row, count);
    const std::vector<std::int32_t> current =
        first ? std::vector<std::int32_t>{}
              : std::vector<std::int32_t>(assignment.begin() + std::ptrdiff_t(first_row),
                                          assignment.begin() + std::ptrdiff_t(first_row + count));
    const AssignmentResult assigned = assign_to_bases(rows, bases, options, current);
    totals[0] += assigned.total_objective();
    for (std::size_t r = 0; r < count; ++r) {
      totals[1] += !first && assignment[first_row + r] != assigned.best[r];
      assignment[first_row + r] = assigned.best[r];
    }
    weights.middleRows(Eigen::Index(first_row), Eigen::Index(count)) = assigned.weights;
    progress.advance(count);
  }
  ranks.sum_everywhere(totals, 2);
  record.objective = totals[0];
  record.changed = std::size_t(totals[1]);
  std::vector<BasisIrlsFit> fits(
      std::size_t(bases.clusters),
      BasisIrlsFit(bases.terms, bases.lights, options.basis_fit.epsilon));
  for (int round = 0; round <= rounds; ++round) {
    const bool solve = round < rounds;
    for (BasisIrlsFit& fit : fits) fit.start_round();
    for (std::size_t first_row = 0; first_row < scratch.rows(); first_row += block_rows) {
      throw_if_interrupted();
      const std::size_t count = std::min(block_rows, scratch.rows() - first_row);
      const WorkingRows rows = scratch.read(first_row, count);
      std::vector<std::vector<std::uint32_t>> members(fits.size());
      for (std::size_t r = 0; r < count; ++r)
        members[std::size_t(assignment[first_row + r])].push_back(std::uint32_t(r));
      parallel_for(members.size(), options.threads, [&](std::size_t k, unsigned) {
        for (const std::uint32_t r : members[k])
          fits[k].add(rows.row(r), weights.row(Eigen::Index(first_row + r)).data(),
                      bases.basis(int(k)), !solve);
      });
      progress.advance(count);
    }
    sum_fits_to_root(ranks, fits);
    if (ranks.root())
      for (int k = 0; k < bases.clusters; ++k)
        fits[std::size_t(k)].end_round(bases.basis(k), solve);
    broadcast_bases(ranks, bases);
  }
  progress.finish();
  if (ranks.root())
    for (int k = 0; k < bases.clusters; ++k) fits[std::size_t(k)].finish(bases.basis(k));
  broadcast_bases(ranks, bases);
  record.seconds = seconds_since(start);
  return record;
}

// The build pass over this rank's rows [begin_row, end_row): the strips read again, assigned to
// the final bases (the last pass's clusters among the candidates) and built, into the part or,
// when `on_disk` is given, appended to it (the part's `sampled` then has the compressed rows of
// the quantization's sample).
BuiltPart build_part(FieldStripReader& reader, const CompressionOptions& options,
                     const CompressionPlan& plan, const CompressionStats& stats,
                     const ClusterModel& bases, const std::vector<float>& dark,
                     const std::vector<std::int32_t>& assignment, std::size_t stored_rows,
                     int begin_row, int end_row, CompressedStripFile* on_disk) {
  const ReflectanceField& header = reader.header();
  const ClusteringOptions& clustering = options.clustering;
  const int lights = header.lights();
  const int cap = residual_row_cap(options, lights);
  const bool by_peak = options.residual_allocation == ResidualAllocation::peak;
  BuiltPart part;
  part.sparse_counts.assign(std::size(sparseness_thresholds), 0.0);
  // The band's arrays are sized once (its stored rows are known from the read pass, and a row
  // keeps at most `cap` residual entries; pages not written are never resident): grown strip by
  // strip they would be copied again and again, each copy a second one in memory. W is filled in
  // place and given to the part at the end.
  const std::size_t in_memory_rows = on_disk ? 0 : stored_rows;
  RowMatrixF weights(Eigen::Index(in_memory_rows), bases.terms);
  part.field.stored_function.reserve(in_memory_rows);
  part.field.cluster.reserve(in_memory_rows);
  part.field.residual.row_offsets.reserve(in_memory_rows + 1);
  part.field.residual.light_index.reserve(in_memory_rows * std::size_t(cap));
  part.field.residual.values.reserve(in_memory_rows * std::size_t(cap));
  if (by_peak) part.peaks.reserve(stored_rows);
  // The quantization's original rows: whole pixel rows, evenly spaced over the field, about as
  // many functions as it measures.
  const std::int64_t row_functions = std::int64_t(header.width) * header.channels;
  const int sample_every = int(std::max<std::int64_t>(
      1, header.height /
             std::max<std::int64_t>(1, std::int64_t(plan.quantization_rows) / row_functions)));
  std::size_t row = 0;
  const auto throw_changed = [&](std::size_t rows_now) {
    throw Error("the field " + reader.path().string() +
                " changed while it was compressed: its second reading has at least " +
                std::to_string(rows_now) + " stored functions in rows " +
                std::to_string(begin_row) + " to " + std::to_string(end_row) + ", the first " +
                std::to_string(stored_rows));
  };
  ProgressReporter progress("compress: building strips", std::uint64_t(end_row - begin_row),
                            clustering.quiet);
  reader.rewind();
  for (int y = begin_row; y < end_row; y += plan.strip_rows) {
    throw_if_interrupted();
    const int rows = std::min(plan.strip_rows, end_row - y);
    const ReflectanceField strip = reader.read(y, rows);
    PreparedRows prepared = prepare_rows(strip, options.transform == BasisTransform::haar,
                                         stats.noise, clustering.threads);
    prepared.dark = dark;
    ClusterModel strip_model = bases;
    const std::size_t count = prepared.rows.rows();
    if (row + count > stored_rows) throw_changed(row + count);
    if (count > 0) {
      const std::vector<std::int32_t> current =
          assignment.empty()
              ? std::vector<std::int32_t>{}
              : std::vector<std::int32_t>(assignment.begin() + std::ptrdiff_t(row),
                                          assignment.begin() + std::ptrdiff_t(row + count));
      AssignmentResult assigned = assign_to_bases(prepared.rows, bases, clustering, current);
      part.objective += assigned.total_objective();
      for (std::size_t r = 0; r < count; ++r)
        part.changed += !current.empty() && current[r] != assigned.best[r];
      strip_model.assignment = std::move(assigned.best);
      strip_model.weights = std::move(assigned.weights);
    }
    CompressionStats strip_stats;
    CompressedField built =
        build_compressed_field(strip, prepared, strip_model, options.transform, cap,
                               stats.residual_threshold, {}, strip_stats, clustering.threads);
    for (std::size_t level = 0; level < part.sparse_counts.size(); ++level)
      part.sparse_counts[level] += strip_stats.sparseness[level] * double(count);
    merge_relative_errors(
        part.float32_masked,
        relative_error(strip, built, true, all_residual_entries, clustering.threads));
    if (by_peak)
      for (const std::uint32_t p : built.stored_function)
        part.peaks.push_back(strip.values.row(p).cwiseAbs().maxCoeff());
    for (int r = (y + sample_every - 1) / sample_every * sample_every; r < y + rows;
         r += sample_every) {
      append_field_rows(part.original_sample, strip, r - y, 1);
      part.sample_rows.emplace_back(r, 1);
      if (on_disk) append_compressed_rows(part.sampled, compressed_rows(built, r - y, 1));
    }
    row += count;
    part.residual_nonzeros += built.residual.nonzeros();
    if (on_disk) {
      on_disk->append(built);
    } else {
      weights.middleRows(Eigen::Index(row - count), Eigen::Index(count)) = built.weights;
      built.weights.resize(0, bases.terms);
      append_compressed_rows(part.field, built);
    }
    progress.advance(std::uint64_t(rows));
  }
  progress.finish();
  if (row != stored_rows) throw_changed(row);
  if (part.field.height > 0 && !on_disk) part.field.weights = std::move(weights);
  return part;
}

// The report's errors of the field `reader` reads, each rank (all call it) measuring its band of
// pixel rows [bands[rank], bands[rank + 1]) strip by strip: `stored_rows(y, rows)` gives the
// compressed field's rows [y, y + rows) of the band (y counted from the band's first row), as
// stored. The root gets the errors merged in rank order.
FieldErrors measure_band_errors(FieldStripReader& reader, const std::vector<int>& bands,
                                int strip_rows,
                                const std::function<CompressedField(int y, int rows)>& stored_rows,
                                int residual_entries, double white,
                                const std::vector<std::uint8_t>& psnr_mask, unsigned threads,
                                bool quiet) {
  Ranks& ranks = process_ranks();
  const int first_row = bands.at(std::size_t(ranks.rank()));
  const int end_row = bands.at(std::size_t(ranks.rank()) + 1);
  const ReflectanceField& header = reader.header();
  const std::int64_t row_functions = std::int64_t(header.width) * header.channels;
  FieldErrors total;
  ProgressReporter progress("compress: measuring the error", std::uint64_t(end_row - first_row),
                            quiet);
  reader.rewind();
  for (int y = first_row; y < end_row; y += strip_rows) {
    throw_if_interrupted();
    const int rows = std::min(strip_rows, end_row - y);
    const ReflectanceField strip = reader.read(y, rows);
    std::vector<std::uint8_t> strip_mask;
    if (!psnr_mask.empty())
      strip_mask.assign(psnr_mask.begin() + std::ptrdiff_t(y) * header.width,
                        psnr_mask.begin() + std::ptrdiff_t(y + rows) * header.width);
    merge_field_errors(total,
                       measure_field_errors(strip, stored_rows(y - first_row, rows),
                                            residual_entries, white, strip_mask, threads),
                       (y - first_row) * row_functions);
    progress.advance(std::uint64_t(rows));
  }
  progress.finish();
  return gather_errors(ranks, std::move(total), first_row * row_functions);
}

}  // namespace

StreamedCompression compress_streamed(FieldStripReader& reader, const CompressionOptions& options,
                                      const CompressionPlan& plan, CompressionStats& stats,
                                      StreamedTrace& trace, const std::string& scratch_name,
                                      const IterationHook& hook, const ClusteringResume* resume) {
  validate_compression_options(options);
  check_streamable_options(options);
  const auto run_start = Clock::now();
  Ranks& ranks = process_ranks();
  const ReflectanceField& header = reader.header();
  const int lights = header.lights();
  const ClusteringOptions& clustering = options.clustering;
  if (clustering.terms >= lights)
    throw Error("terms per cluster (" + std::to_string(clustering.terms) +
                ") must be fewer than the lights (" + std::to_string(lights) + ")");
  reader.rewind();
  stats.noise = estimate_streamed_noise(reader.read(0, std::min(plan.strip_rows, header.height)),
                                        options.noise_floor, clustering.threads);
  stats.residual_threshold = options.residual_threshold >= 0
                                 ? options.residual_threshold
                                 : default_residual_threshold(stats.noise, header);
  // 1. Read this rank's even share of the pixel rows: scratch rows, the dark model's sums, every
  // row's stored functions; counts over all ranks.
  auto start = Clock::now();
  const RankShare read_band = rank_share(ranks, header.height);
  auto scratch =
      std::make_unique<ScratchRows>(plan.scratch_folder, scratch_name, lights, clustering.threads);
  const ReadResult read =
      read_strips(reader, options, plan, stats.noise, read_band.first, read_band.end, *scratch);
  std::vector<double> sums{double(read.dark_pixels), double(read.outside_mask),
                           double(scratch->bytes())};
  sums.resize(3 + std::size_t(header.height), 0.0);
  std::copy(read.stored_per_row.begin(), read.stored_per_row.end(),
            sums.begin() + std::ptrdiff_t(3 + std::size_t(read_band.first)));
  ranks.sum_everywhere(sums.data(), sums.size());
  stats.dark_pixels = std::size_t(sums[0]);
  stats.outside_mask = std::int64_t(sums[1]);
  trace.scratch_bytes = std::uint64_t(sums[2]);
  // The field's stored functions before every pixel row (row_start[y]).
  std::vector<std::uint64_t> stored_per_row, row_start{0};
  for (int y = 0; y < header.height; ++y) {
    stored_per_row.push_back(std::uint64_t(sums[3 + std::size_t(y)]));
    row_start.push_back(row_start.back() + stored_per_row.back());
  }
  stats.stored_rows = std::size_t(row_start.back());
  std::vector<float> dark;
  if (stats.dark_pixels > 0) {
    dark = stats.noise.shape;
    if (options.transform == BasisTransform::haar)
      for (int c = 0; c < header.channels; ++c)
        haar_forward(dark.data() + std::size_t(c) * lights, lights, 1);
  }
  trace.strips = (header.height + plan.strip_rows - 1) / plan.strip_rows;
  stats.functions = std::int64_t(header.pixels()) * header.channels;
  stats.all_zero = stats.functions - stats.outside_mask - std::int64_t(stats.stored_rows) -
                   std::int64_t(stats.dark_pixels) * header.channels;
  stats.clusters_asked = clustering.clusters;
  trace.read_seconds = stats.prepare_seconds = seconds_since(start);

  // The refinement passes' bands hold as many stored functions as whole pixel rows allow (dark and
  // masked pixels store none): the ranks move their scratch rows to match.
  const std::size_t block_rows =
      std::max<std::size_t>(1, std::size_t(plan.strip_rows) * header.width * header.channels);
  // The first stored function of every band of `bands`, and the field's end.
  const auto band_starts = [&](const std::vector<int>& bands) {
    std::vector<std::uint64_t> starts;
    for (const int y : bands) starts.push_back(row_start[std::size_t(y)]);
    return starts;
  };
  const std::vector<int> refine_bands = weighted_shares(stored_per_row, ranks.size());
  const std::vector<std::uint64_t> refine_starts = band_starts(refine_bands);
  const int begin_row = refine_bands[std::size_t(ranks.rank())];
  for (int r = 0; r < ranks.size(); ++r)
    trace.rank_stored_rows.push_back(refine_starts[std::size_t(r) + 1] -
                                     refine_starts[std::size_t(r)]);
  if (ranks.size() > 1) {
    std::vector<int> read_bands;
    for (int r = 0; r < ranks.size(); ++r)
      read_bands.push_back(rank_share(ranks, header.height, r).first);
    read_bands.push_back(header.height);
    auto balanced = std::make_unique<ScratchRows>(plan.scratch_folder, scratch_name + ".balanced",
                                                  lights, clustering.threads);
    move_scratch_rows(ranks, *scratch, band_starts(read_bands), refine_starts, block_rows,
                      *balanced);
    scratch = std::move(balanced);
  }
  // The build pass and the error measure read all of their pixel rows' functions too: reading and
  // preparing one costs about 0.4 of building a stored function (docs/scale.md), and their bands
  // hold even shares of both.
  std::vector<std::uint64_t> build_cost;
  const std::uint64_t row_functions = std::uint64_t(header.width) * header.channels;
  for (const std::uint64_t stored : stored_per_row)
    build_cost.push_back(5 * stored + 2 * row_functions);
  StreamedCompression result;
  result.bands = weighted_shares(build_cost, ranks.size());
  const int build_begin = result.bands[std::size_t(ranks.rank())];
  const int build_end = result.bands[std::size_t(ranks.rank()) + 1];

  // 2. Fit on the sample (the same rows whatever the ranks), gathered at the root; its bases go
  // to every rank.
  start = Clock::now();
  ClusterModel bases;
  {
    const std::size_t stride = std::size_t(
        std::max<std::uint64_t>(1, (functions_inside_mask(header) + plan.sample_rows - 1) /
                                       std::max<std::size_t>(plan.sample_rows, 1)));
    const WorkingRows sample =
        gather_sample(ranks, sample_rows(*scratch, row_start[std::size_t(begin_row)], stride));
    trace.sample_rows = sample.rows();
    if (ranks.root()) {
      // The other ranks on this machine wait for the bases: their threads, on their cores,
      // cluster the sample too (the model does not depend on the thread count).
      const LocalCoresLease lease(ranks);
      CompressionOptions sample_options = options;
      sample_options.clustering.threads = lease.threads(clustering.threads);
      trace.sample_clustering_cores = lease.cores();
      trace.sample_clustering_threads = resolve_thread_count(sample_options.clustering.threads);
      ClusterModel model =
          cluster_prepared_rows(sample, lights, sample_options, stats, hook, resume);
      bases.terms = model.terms;
      bases.lights = model.lights;
      bases.clusters = model.clusters;
      bases.bases = std::move(model.bases);
    }
    broadcast_bases(ranks, bases);
  }
  trace.sample_clustering_seconds = seconds_since(start);

  // 3. Refine over the scratch rows.
  const auto refine_start = Clock::now();
  std::vector<std::int32_t> assignment;
  RowMatrixF weights;
  // Like the in-memory iterations, the passes stop once few rows change cluster.
  for (int pass = 1; bases.clusters > 0 && pass <= options.refine_iterations; ++pass) {
    trace.passes.push_back(
        refine_pass(ranks, *scratch, block_rows, clustering, bases, assignment, weights, pass));
    if (pass > 1 && double(trace.passes.back().changed) <=
                        clustering.settle_fraction * double(stats.stored_rows))
      break;
  }
  weights = {};
  trace.refine_seconds = seconds_since(refine_start);
  stats.clustering_seconds = seconds_since(start);

  // 4. Build: the strips again, assigned to the final bases; the parts gathered at the root.
  start = Clock::now();
  stats.residual_entries = options.residual.entries_for(lights);
  if (plan.compressed_on_disk)
    result.strips =
        std::make_unique<CompressedStripFile>(plan.scratch_folder, scratch_name + ".compressed");
  const std::vector<std::uint64_t> build_starts = band_starts(result.bands);
  if (ranks.size() > 1 && !assignment.empty())
    assignment = move_assignment(ranks, assignment, refine_starts, build_starts);
  const std::size_t build_rows =
      build_starts[std::size_t(ranks.rank()) + 1] - build_starts[std::size_t(ranks.rank())];
  const auto build_part_start = Clock::now();
  BuiltPart built = build_part(reader, options, plan, stats, bases, dark, assignment, build_rows,
                               build_begin, build_end, result.strips.get());
  const double build_part_seconds = seconds_since(build_part_start);
  std::vector<BuiltPart> parts = gather_parts(ranks, std::move(built));
  if (result.strips) {
    result.band_strips = result.strips->strips();
    result.strips->shell().bases = bases.bases;
    gather_strips_to_root(ranks, *result.strips);
  }
  // Every rank's time outside the exchanges, bytes sent and seconds building its band, at the
  // root.
  std::vector<double> rank_figures(3 * std::size_t(ranks.size()), 0.0);
  double* own_figures = rank_figures.data() + 3 * ranks.rank();
  own_figures[0] = seconds_since(run_start) - ranks.exchange_seconds();
  own_figures[1] = double(ranks.bytes_sent());
  own_figures[2] = build_part_seconds;
  ranks.sum_to_root(rank_figures.data(), rank_figures.size());
  if (!ranks.root()) return result;
  for (int r = 0; r < ranks.size(); ++r) {
    trace.rank_compute_seconds.push_back(rank_figures[3 * std::size_t(r)]);
    trace.rank_bytes_sent.push_back(std::uint64_t(rank_figures[3 * std::size_t(r) + 1]));
    trace.rank_build_seconds.push_back(rank_figures[3 * std::size_t(r) + 2]);
  }

  CompressedField& out = result.strips ? result.strips->shell() : result.field;
  StreamedPass build;
  build.pass = int(trace.passes.size()) + 1;
  std::vector<double> sparse(std::size(sparseness_thresholds), 0.0), peak;
  std::size_t entries = 0;
  for (const BuiltPart& part : parts) entries += part.field.residual.values.size();
  if (result.strips) stats.residual_nonzeros = 0;
  for (BuiltPart& part : parts) {
    if (result.strips) {
      stats.residual_nonzeros += part.residual_nonzeros;
      append_compressed_rows(result.sampled, part.sampled);
    } else if (out.height == 0) {
      out = std::move(part.field);  // one rank's part is the field: no copy
      // Room for the other ranks' parts, each freed as it is stacked.
      out.stored_function.reserve(stats.stored_rows);
      out.cluster.reserve(stats.stored_rows);
      out.residual.row_offsets.reserve(stats.stored_rows + 1);
      out.residual.light_index.reserve(entries);
      out.residual.values.reserve(entries);
    } else {
      append_compressed_rows(out, part.field);
    }
    part.field = {};
    peak.insert(peak.end(), part.peaks.begin(), part.peaks.end());
    for (std::size_t level = 0; level < sparse.size(); ++level)
      sparse[level] += part.sparse_counts[level];
    build.objective += part.objective;
    merge_relative_errors(result.float32_masked, part.float32_masked);
    build.changed += std::size_t(part.changed);
    if (part.original_sample.height > 0) {
      append_field_rows(result.original_sample, part.original_sample, 0,
                        part.original_sample.height);
      result.sample_rows.insert(result.sample_rows.end(), part.sample_rows.begin(),
                                part.sample_rows.end());
    }
  }
  build.seconds = seconds_since(start);
  trace.passes.push_back(build);
  out.clusters = bases.clusters;
  out.bases = bases.bases;
  if (options.residual_allocation == ResidualAllocation::peak)
    keep_largest_relative_to_peak(out.residual, peak,
                                  std::size_t(stats.residual_entries) * out.stored_rows());
  if (!result.strips) stats.residual_nonzeros = out.residual.nonzeros();
  stats.sparseness.assign(sparse.size(), 0.0);
  for (std::size_t level = 0; level < sparse.size(); ++level)
    stats.sparseness[level] =
        stats.stored_rows == 0 ? 0.0 : sparse[level] / double(stats.stored_rows);
  stats.clusters = bases.clusters;
  stats.residual_seconds = trace.build_seconds = seconds_since(start);
  return result;
}

FieldErrors measure_errors_on_disk(FieldStripReader& reader, const std::vector<int>& bands,
                                   int strip_rows, const CompressedStripFile& strips,
                                   std::size_t band_strips, const StripStorage& storage,
                                   int residual_entries, double white,
                                   const std::vector<std::uint8_t>& psnr_mask, unsigned threads,
                                   bool quiet) {
  return measure_band_errors(
      reader, bands, strip_rows,
      [&](int y, int rows) {
        const std::size_t s = std::size_t(y / strip_rows);
        if (s >= band_strips) throw Error("internal: the error measure's band has more strips");
        CompressedField strip = storage.store(strips.read(s));
        if (strip.height != rows)
          throw Error("internal: the error measure's strips are not the build's");
        return strip;
      },
      residual_entries, white, psnr_mask, threads, quiet);
}

FieldErrors measure_streamed_errors(FieldStripReader& reader, const std::vector<int>& bands,
                                    int strip_rows, const CompressedField& stored,
                                    int residual_entries, double white,
                                    const std::vector<std::uint8_t>& psnr_mask, unsigned threads,
                                    bool quiet) {
  // One process measures `stored` itself; several get their bands from the root.
  std::optional<CompressedField> received;
  if (process_ranks().size() > 1) received = scatter_bands(process_ranks(), stored, bands);
  const CompressedField& stored_band = received ? *received : stored;
  return measure_band_errors(
      reader, bands, strip_rows,
      [&](int y, int rows) { return compressed_rows(stored_band, y, rows); }, residual_entries,
      white, psnr_mask, threads, quiet);
}

}  // namespace relume
