// The memory plan of a compression: in memory when compressing the field whole (about twice its
// float32 size plus the model) fits the budget, else streamed (compress/streamed_compression.hpp)
// with strips, a clustering sample and a quantization sample sized to fit, or refused with the
// numbers when not even one row of pixels and the model fit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "compress/clustered_factorization.hpp"

namespace relume {

struct CompressionPlan {
  bool streamed = false;
  std::uint64_t budget = 0;           // bytes the run may use for its data
  std::string budget_source;          // "--memory-limit", "MemAvailable", ...
  std::uint64_t field_bytes = 0;      // the field as float32
  std::uint64_t in_memory_bytes = 0;  // estimated need of the in-memory path
  // The process's resident memory when planned (its code, libraries, the OpenCL runtime): the
  // budget is for what the compression allocates on top.
  std::uint64_t resident_bytes = 0;
  // Streamed only:
  int strip_rows = 0;                 // pixel rows per strip
  std::size_t sample_rows = 0;        // the clustering sample's rows, at most
  std::size_t quantization_rows = 0;  // original functions kept to choose the quantization on
  std::uint64_t model_bytes = 0;      // the compressed field, its copies and the pass state
  std::uint64_t scratch_bytes = 0;    // the scratch file, at most
  // The compressed field is built into a file in the scratch folder (every rank its band's; the
  // root gathers them into its own) and written to the container strip by strip, never held
  // whole: when holding it would take more than half the budget (not with the peak residual
  // allocation, which ranks the entries of the whole field).
  bool compressed_on_disk = false;
  std::filesystem::path scratch_folder;

  std::string describe() const;  // one line for the user
};

// The plan for a field of `header`'s shape (values empty; mask set) within `budget` bytes, with
// `threads` workers: in memory when the estimate fits (and `stream_anyway` is false: several
// ranks always stream), else streamed with the tallest strips and the largest sample that fit
// (the compressed field on disk when it would take more than half the budget).
// Throws Error with the numbers when even a one-row strip and the model do not fit.
CompressionPlan plan_compression(const ReflectanceField& header, const CompressionOptions& options,
                                 std::uint64_t budget, const std::string& budget_source,
                                 unsigned threads, const std::filesystem::path& scratch_folder,
                                 bool stream_anyway = false);

// Throws Error naming the first option that needs the whole field in memory (clustered PCA,
// multi-resolution, light weighting, the trimmed refit, an exact refit).
void check_streamable_options(const CompressionOptions& options);

// Stored rows at most: the functions of the pixels inside `header`'s mask (all without one).
std::uint64_t functions_inside_mask(const ReflectanceField& header);

// The residual entries a stored row may hold (more than the budget under peak allocation).
int residual_row_cap(const CompressionOptions& options, int lights);

}  // namespace relume
