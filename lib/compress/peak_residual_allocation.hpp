// Residual allocation by peak (`relume compress --residual-allocation peak`, issue 17): instead of
// the same n entries in every function, the field's n x stored-rows entries go to the residual
// values largest relative to their function's peak, |E[p,i]| / max_i |R[p,i]|. Every row keeps a
// prefix of its sorted entries, so the dynamic residual still works; a function whose fit is
// already close gives its entries to one with a sharp feature (a shadow terminator, a highlight)
// that its cluster's basis misses. In the light basis this makes the largest per-light error
// relative to the peak that any function leaves as small as that many entries allow (the
// minimax allocation); the per-light error is what a concentrated light (a sun) shows undiluted.
#pragma once

#include <cstddef>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// With allocation `peak`, compress_field first keeps up to this many times the budget's entries
// per function (at most all lights), then the field's budget among them.
inline constexpr int peak_allocation_row_cap = 4;

// Rows of `residual` must be sorted by |value| descending (as stored); `peak` holds each row's
// max_i |R[p,i]| (rows with peak 0 keep nothing). Keeps the `total_entries` entries with the
// largest |value| / peak over all rows (a few more where values tie at the cut), each row a
// prefix of itself.
void keep_largest_relative_to_peak(ResidualRows& residual, const std::vector<double>& peak,
                                   std::size_t total_entries);

}  // namespace relume
