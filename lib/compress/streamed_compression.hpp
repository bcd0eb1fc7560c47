// Compression of a field larger than memory (the streamed plan): the field is read strip by
// strip (field/field_strips.hpp) and never held whole.
//  1. Read: every strip's functions are prepared (compress/cluster_model.hpp) and their unit rows
//     go to a float16 scratch file (compress/scratch_rows.hpp).
//  2. Fit on a sample: every s-th scratch row in scan order (a spatially stratified sample) is
//     clustered as a whole field would be, with its checkpoints and --resume.
//  3. Refine: each pass streams the scratch rows block by block, assigns them to the clusters
//     (their W refitted) and sums every cluster's IRLS normal equations for the F-step
//     (compress/cluster_basis.hpp), which add across blocks; the new bases follow each pass.
//  4. Build: the strips are read again; each is assigned to the final bases and its residual cut
//     (build_compressed_field), and the strips' compressed fields are stacked in memory or, when
//     the plan says so, kept on disk (compress/compressed_strip_file.hpp).
// The memory plan (compress/compression_plan.hpp) says whether a field needs this and with what
// strips.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compress/clustered_factorization.hpp"
#include "compress/compressed_strip_file.hpp"
#include "compress/compression_plan.hpp"
#include "compress/storage_precision.hpp"
#include "compress/field_errors.hpp"
#include "field/field_strips.hpp"

namespace relume {

struct StreamedPass {
  int pass = 0;             // 1, 2, ... (the refinement passes), then the build pass
  double objective = 0;     // sum of the rows' L1 residual under the bases assigned to
  std::size_t changed = 0;  // rows whose cluster changed since the previous pass
  double seconds = 0;
};

struct StreamedTrace {
  std::size_t sample_rows = 0;
  // The threads that clustered the sample at the root, and the cores they could run on (the root
  // borrows those of the ranks on its machine, which wait for its bases).
  unsigned sample_clustering_threads = 0, sample_clustering_cores = 0;
  std::uint64_t scratch_bytes = 0;  // over all ranks
  int strips = 0;
  double read_seconds = 0, sample_clustering_seconds = 0, refine_seconds = 0, build_seconds = 0;
  std::vector<StreamedPass> passes;
  // Per rank (core/ranks.hpp): stored functions of its band, seconds outside the exchanges
  // between ranks, bytes sent, and seconds its build pass took (before the parts are gathered).
  std::vector<std::uint64_t> rank_stored_rows;
  std::vector<double> rank_compute_seconds;
  std::vector<std::uint64_t> rank_bytes_sent;
  std::vector<double> rank_build_seconds;
};

struct StreamedCompression {
  CompressedField field;  // float32, as compress_field returns it (empty with `strips`)
  // With the plan's compressed field on disk: its strips (float32, as built), and the compressed
  // rows of `original_sample` (what store_with_precision_on_strips cuts out of `field`). Every
  // rank's file starts with its band's `band_strips` strips; the root's holds every rank's after.
  std::unique_ptr<CompressedStripFile> strips;
  std::size_t band_strips = 0;
  CompressedField sampled;
  // Eq. 16 of `field` over the masked functions, measured strip by strip as it was built (so
  // that no float32 copy need be kept after quantization).
  RelativeError float32_masked;
  // Evenly spaced pixel rows of the original, stacked, and where they are (first row, rows):
  // what the quantization is chosen against (store_with_precision_on_strips).
  ReflectanceField original_sample;
  std::vector<std::pair<int, int>> sample_rows;
  // Rank r's pixel rows [bands[r], bands[r + 1]) of the build pass and the error measure (every
  // rank's result has them).
  std::vector<int> bands;
};

// Compresses the field `reader` reads with `plan` (streamed); the scratch file is
// `.tmp-<pid>-<scratch_name>` in the plan's folder. `hook` and `resume` apply to the sample's
// clustering (checkpoints of the sample's model). `stats` is filled as compress_field fills it.
// With several ranks (core/ranks.hpp: mpirun), each reads an even share of the pixel rows, then
// the ranks move their scratch rows so that each refines and builds a band of rows with as many
// stored functions as the others; the root clusters the gathered sample, solves every F-step from
// the summed normal equations and receives the parts: only the root's result holds the field
// (the others' has only the bands and, on disk, their own band's strips).
StreamedCompression compress_streamed(FieldStripReader& reader, const CompressionOptions& options,
                                      const CompressionPlan& plan, CompressionStats& stats,
                                      StreamedTrace& trace, const std::string& scratch_name,
                                      const IterationHook& hook = {},
                                      const ClusteringResume* resume = nullptr);

// The report's errors of `stored` against the field `reader` reads, strip by strip
// (field_errors.hpp). With several ranks (core/ranks.hpp) every rank calls it with the bands of
// its compression (StreamedCompression::bands): the root, which holds `stored` (ignored
// elsewhere), sends each rank its band of pixel rows, each measures its band, and the root gets
// the merged errors.
FieldErrors measure_streamed_errors(FieldStripReader& reader, const std::vector<int>& bands,
                                    int strip_rows, const CompressedField& stored,
                                    int residual_entries, double white,
                                    const std::vector<std::uint8_t>& psnr_mask, unsigned threads,
                                    bool quiet);

// measure_streamed_errors of a field whose strips are on disk: every rank (all call it) measures
// its band from the first `band_strips` strips of its own `strips`, each stored as `storage`
// says (broadcast_strip_storage); the root gets the merged errors.
FieldErrors measure_errors_on_disk(FieldStripReader& reader, const std::vector<int>& bands,
                                   int strip_rows, const CompressedStripFile& strips,
                                   std::size_t band_strips, const StripStorage& storage,
                                   int residual_entries, double white,
                                   const std::vector<std::uint8_t>& psnr_mask, unsigned threads,
                                   bool quiet);

}  // namespace relume
