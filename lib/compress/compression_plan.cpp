// Implementation of the compression's memory plan (see compression_plan.hpp).
#include "compress/compression_plan.hpp"

#include <algorithm>
#include <cstdio>
#include <relume/error.hpp>

#include "compress/cluster_assignment.hpp"
#include "compress/peak_residual_allocation.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "model/quantization.hpp"

namespace relume {
namespace {

// Bytes of the clustering sample per row per light: the rows, the seeding's sample copy and the
// clustering's working copies.
constexpr std::uint64_t sample_bytes_per_value = 12;

// Rows a whole-field quantization choice measures (QuantizationBudget::sample_rows).
constexpr std::uint64_t quantization_sample_rows = QuantizationBudget{}.sample_rows;

// A strip's float32 values at most (the refinement passes' blocks of scratch rows are a strip's
// functions too). Taller strips only save reads, but arrays above glibc's largest mmap threshold
// (32 MiB) are mapped fresh and faulted in page by page every time one is allocated: with 160 MB
// strips at 1280 x 1280 x 253, the passes spent more time in the kernel than computing.
constexpr std::uint64_t strip_value_bytes_at_most = std::uint64_t(16) << 20;

// What the clustering holds per cluster (its normal equations, best and current bases) and what
// its candidate search holds: at 100,000 clusters hundreds of MB that the plan once left out.
std::uint64_t clustering_state_bytes(const CompressionOptions& options, std::uint64_t lights,
                                     unsigned threads) {
  const std::uint64_t terms = std::uint64_t(options.clustering.terms);
  const std::uint64_t clusters = std::uint64_t(options.clustering.clusters);
  return clusters * lights * (terms * (terms + 1) / 2 + 3 * terms + 2) * 8 +
         candidate_search_bytes(options.clustering.clusters, options.clustering.terms,
                                int(lights), resolve_thread_count(threads));
}

}  // namespace

std::uint64_t functions_inside_mask(const ReflectanceField& header) {
  std::uint64_t inside = 0;
  for (const std::uint8_t value : header.mask) inside += value != 0;
  if (header.mask.empty()) inside = std::uint64_t(header.pixels());
  return inside * std::uint64_t(header.channels);
}

int residual_row_cap(const CompressionOptions& options, int lights) {
  const int entries = options.residual.entries_for(lights);
  return options.residual_allocation == ResidualAllocation::peak
             ? std::min(lights, entries * peak_allocation_row_cap)
             : entries;
}

std::string CompressionPlan::describe() const {
  char line[1024];
  if (!streamed) {
    std::snprintf(line, sizeof line,
                  "plan: in memory (the field is %s as float32, compressing it needs about %s "
                  "on top of the %s the process holds; the budget is %s, %s)",
                  byte_size_text(field_bytes).c_str(), byte_size_text(in_memory_bytes).c_str(),
                  byte_size_text(resident_bytes).c_str(), byte_size_text(budget).c_str(),
                  budget_source.c_str());
  } else {
    std::snprintf(line, sizeof line,
                  "plan: streamed (the field is %s as float32, in memory it would need about %s; "
                  "the budget is %s, %s, on top of the %s the process holds): strips of %d pixel "
                  "rows, a clustering sample of up to "
                  "%zu functions, scratch of up to %s in %s, model and pass state about %s%s, "
                  "quantization measured on %zu original functions",
                  byte_size_text(field_bytes).c_str(), byte_size_text(in_memory_bytes).c_str(),
                  byte_size_text(budget).c_str(), budget_source.c_str(),
                  byte_size_text(resident_bytes).c_str(), strip_rows, sample_rows,
                  byte_size_text(scratch_bytes).c_str(), scratch_folder.string().c_str(),
                  byte_size_text(model_bytes).c_str(),
                  compressed_on_disk ? " (the compressed field on disk)" : "", quantization_rows);
  }
  return line;
}

CompressionPlan plan_compression(const ReflectanceField& header, const CompressionOptions& options,
                                 std::uint64_t budget, const std::string& budget_source,
                                 unsigned threads, const std::filesystem::path& scratch_folder,
                                 bool stream_anyway) {
  const std::uint64_t lights = std::uint64_t(header.lights());
  const std::uint64_t terms = std::uint64_t(options.clustering.terms);
  const std::uint64_t clusters = std::uint64_t(options.clustering.clusters);
  const std::uint64_t functions = functions_inside_mask(header);
  const std::uint64_t row_functions = std::uint64_t(header.width) * header.channels;
  CompressionPlan plan;
  plan.budget = budget;
  plan.budget_source = budget_source;
  plan.resident_bytes = resident_memory_bytes();
  plan.field_bytes = std::uint64_t(header.pixels()) * header.channels * lights * sizeof(float);
  // One copy of the compressed field: W, the residual's indices and values, row and cluster
  // indices. In memory it is held as built, as stored and as quantized.
  const std::uint64_t compressed =
      functions * (terms * 4 + std::uint64_t(residual_row_cap(options, int(lights))) * 8 + 8);
  const std::uint64_t clustering = clustering_state_bytes(options, lights, threads);
  plan.in_memory_bytes = 2 * plan.field_bytes + 3 * compressed + clustering;
  if (plan.in_memory_bytes <= budget && !stream_anyway) return plan;

  plan.streamed = true;
  plan.scratch_folder = scratch_folder;
  plan.scratch_bytes = functions * lights * 2;
  // Streamed it is built in place and quantized in place, so held once, next to the container
  // encoder's byte sections (at most three quarters of it: integers of 1 and 2 bytes where it
  // holds 4) and every row's norm, cluster, function index (and peak). On disk, the build holds
  // every row's norm and cluster, and the writer every row's function index and the mask. The
  // refinement passes before it hold every row's norm, cluster and weights instead. All with the
  // clusters' normal equations, best and current bases.
  const bool by_peak = options.residual_allocation == ResidualAllocation::peak;
  const std::uint64_t build_in_memory =
      compressed + compressed / 4 * 3 + functions * (by_peak ? 24 : 16);
  // It goes to disk when holding it would take more than half of what the plan may use (the
  // rest is for the sample and the strips), unless the peak allocation keeps it in memory (it
  // ranks the entries of the whole field). The rule is the same for any number of ranks, so that
  // they plan alike.
  plan.compressed_on_disk = !by_peak && build_in_memory > budget / 20 * 17 / 2;
  const std::uint64_t build =
      plan.compressed_on_disk ? functions * 8 + std::uint64_t(header.pixels()) : build_in_memory;
  // On disk: the compressed strips, then the container's raw row sections and their codings.
  if (plan.compressed_on_disk) plan.scratch_bytes += 2 * compressed;
  const std::uint64_t refine = functions * (8 + terms * 4);
  plan.model_bytes = std::max(build, refine) + clustering;
  // Per pixel row of a strip: the strip's field, its prepared rows, the built rows and the
  // error measure's reconstruction, and every reading thread's decoded image rows.
  const std::uint64_t strip_row_bytes =
      row_functions * lights * 4 * 4 +
      std::uint64_t(resolve_thread_count(threads)) * header.width * 4 * sizeof(float);
  const std::uint64_t sample_row_bytes = lights * sample_bytes_per_value;
  const std::uint64_t original_row_bytes = lights * sizeof(float);
  const std::uint64_t fewest_sample = std::min<std::uint64_t>(functions, 16 * clusters);
  const std::uint64_t least = plan.model_bytes + strip_row_bytes +
                              fewest_sample * sample_row_bytes + row_functions * original_row_bytes;
  if (budget / 20 * 17 < least)
    throw Error("the memory budget of " + byte_size_text(budget) + " (" + budget_source +
                ") cannot hold even a one-row strip of this " + std::to_string(header.width) + "x" +
                std::to_string(header.height) + "x" + std::to_string(lights) +
                " field with its model: that needs about " + byte_size_text(least) + " (model " +
                byte_size_text(plan.model_bytes) + ", strip row " +
                byte_size_text(strip_row_bytes) + ", clustering sample " +
                byte_size_text(fewest_sample * sample_row_bytes) +
                "); raise --memory-limit or compress fewer clusters or terms");
  // Planned within 85% of the budget: the rest is for what the estimates leave out (allocator
  // overhead, the image decoders' and compressors' buffers).
  std::uint64_t left = budget / 20 * 17 - std::min(budget / 20 * 17, plan.model_bytes);
  // An eighth of what is left to the quantization's original rows, two thirds of the rest to the
  // clustering sample (the more rows the clusters are found on, the closer the result is to the
  // in-memory one), the rest to the strips (their height only sets how many reads there are, up
  // to strip_value_bytes_at_most).
  plan.quantization_rows = std::size_t(std::clamp<std::uint64_t>(
      left / 8 / original_row_bytes, row_functions,
      std::min<std::uint64_t>(functions, quantization_sample_rows) + row_functions));
  left -= plan.quantization_rows * original_row_bytes;
  plan.sample_rows = std::size_t(
      std::max(fewest_sample, std::min<std::uint64_t>(functions, left / 3 * 2 / sample_row_bytes)));
  const std::uint64_t for_strips = left - std::min(left, plan.sample_rows * sample_row_bytes);
  const std::uint64_t tallest =
      std::max<std::uint64_t>(1, strip_value_bytes_at_most / (row_functions * lights * 4));
  plan.strip_rows = int(std::clamp<std::uint64_t>(for_strips / strip_row_bytes, 1,
                                                  std::min<std::uint64_t>(tallest, header.height)));
  return plan;
}

void check_streamable_options(const CompressionOptions& options) {
  const char* option = nullptr;
  if (options.method == CompressionMethod::cpca)
    option = "--method cpca";
  else if (options.multires_levels > 0)
    option = "--multires";
  else if (options.light_weighting > 0)
    option = "--light-weighting";
  else if (options.trimmed_refit_rounds >= 0)
    option = "--trimmed-refit";
  else if (options.clustering.exact_refit)
    option = "--solver (an exact refit)";
  if (option)
    throw Error(std::string(option) +
                " needs the whole field in memory, which does not fit the memory budget here "
                "(the plan is streamed): leave it out, or raise --memory-limit");
}

}  // namespace relume
