// What the ranks of a distributed streamed compression (core/ranks.hpp) exchange, packed into
// bytes: scratch rows (moved between ranks so that their bands hold even work) and the rows'
// clusters (moved again for the build pass's bands), every rank's
// share of the clustering sample (gathered at the root, which clusters it),
// the bases (broadcast by the root after every solve), the F-step's sums (added up at the root),
// every rank's part of the compressed field (gathered at the root, which writes the file; on disk,
// strip by strip), then every rank's band of the stored field (sent by the root; on disk, how to
// store its own strips) and the errors each rank measured on it (merged at the root). With one
// process each is a plain copy.
#pragma once

#include <relume/compressed_field.hpp>
#include <string>
#include <utility>
#include <vector>

#include "compress/cluster_basis.hpp"
#include "compress/cluster_model.hpp"
#include "compress/compressed_strip_file.hpp"
#include "compress/field_errors.hpp"
#include "compress/scratch_rows.hpp"
#include "compress/storage_precision.hpp"
#include "core/ranks.hpp"

namespace relume {

// Every rank's sample rows, stacked in rank order, at the root (empty elsewhere).
WorkingRows gather_sample(Ranks& ranks, const WorkingRows& local);

// The root's clusters, terms, lights and bases into every rank's `model` (its assignment and
// weights are left alone).
void broadcast_bases(Ranks& ranks, ClusterModel& model);

// Adds every rank's round sums of every cluster into the root's `fits`.
void sum_fits_to_root(Ranks& ranks, std::vector<BasisIrlsFit>& fits);

// Moves scratch rows between the ranks (all call it), numbered globally as the ranks' stores
// stacked in rank order: rank r holds rows [held[r], held[r + 1]) in `from` and gets rows
// [wanted[r], wanted[r + 1]) appended to `to`, in order; each round brings every rank at most
// `block_rows` rows.
void move_scratch_rows(Ranks& ranks, const ScratchRows& from,
                       const std::vector<std::uint64_t>& held,
                       const std::vector<std::uint64_t>& wanted, std::size_t block_rows,
                       ScratchRows& to);

// Moves every stored row's cluster between the ranks (all call it), numbered as in
// move_scratch_rows: rank r holds the clusters of rows [held[r], held[r + 1]) in `assignment` and
// gets those of rows [wanted[r], wanted[r + 1]), in order.
std::vector<std::int32_t> move_assignment(Ranks& ranks, const std::vector<std::int32_t>& assignment,
                                          const std::vector<std::uint64_t>& held,
                                          const std::vector<std::uint64_t>& wanted);

// One rank's part of the build pass: its rows of the compressed field (float32) and what the
// root needs with them.
struct BuiltPart {
  CompressedField field;
  std::vector<double> peaks;          // per stored row, for the peak residual allocation
  std::vector<double> sparse_counts;  // per sparseness threshold, rows x share summed
  double objective = 0, changed = 0;  // the build assignment's L1 residual, cluster changes
  RelativeError float32_masked;       // Eq. 16 of `field` over its masked functions
  ReflectanceField original_sample;   // the quantization's original pixel rows
  std::vector<std::pair<int, int>> sample_rows;
  // With the strips on disk (CompressedStripFile) only: the residual entries built and the
  // compressed rows of original_sample's pixel rows.
  std::uint64_t residual_nonzeros = 0;
  CompressedField sampled;
};

// Every rank's part at the root, in rank order (the root's own first); empty elsewhere.
std::vector<BuiltPart> gather_parts(Ranks& ranks, BuiltPart&& local);

// This rank's pixel rows [bands[rank], bands[rank + 1]) of the root's `whole` field (ignored
// elsewhere), as a compressed field of their own (compressed_rows).
// With the compressed field on disk: every other rank's strips (its band's, as built) appended to
// the root's `strips` in rank order (the root's own come first); the other ranks keep theirs.
void gather_strips_to_root(Ranks& ranks, CompressedStripFile& strips);

// The root's `storage` into every rank's, so that each stores its own strips as the root does.
void broadcast_strip_storage(Ranks& ranks, StripStorage& storage);

CompressedField scatter_bands(Ranks& ranks, const CompressedField& whole,
                              const std::vector<int>& bands);

// Every rank's errors of its band (its first function `first_function` of the field) merged at
// the root in rank order, as measuring the bands stacked gives (merge_field_errors); this rank's
// own elsewhere.
FieldErrors gather_errors(Ranks& ranks, FieldErrors local, std::int64_t first_function);

}  // namespace relume
