// Residual selection (paper section 3.4): from a dense residual row E[p,:] = R[p,:] - W[p,:] F,
// entries with |value| <= a threshold are dropped and at most n of the largest are kept, stored
// sorted by |value| descending (ties by ascending light index) with their light index, so every
// prefix of a row is the best residual of that length.
#pragma once

#include <relume/compressed_field.hpp>
#include <relume/residual_budget.hpp>
#include <string>
#include <vector>

namespace relume {

// How the residual budget is spread over the functions: `per_function` keeps the budget's n
// largest entries of every function (paper section 3.4); `peak` keeps n x functions entries over
// the whole field, those largest relative to their function's peak
// (compress/peak_residual_allocation.hpp).
enum class ResidualAllocation { per_function, peak };

// "per-function" or "peak"; throws Error naming the bad text.
ResidualAllocation parse_residual_allocation(const std::string& text);
const char* to_string(ResidualAllocation allocation);

// Appends one row to `rows` (whose row_offsets must already hold the row's start): the entries of
// residual[0..lights) with |value| > threshold, the `max_entries` largest in |value| (all of them
// when max_entries < 0), sorted by |value| descending, ties by light index. `scratch` is reused
// between calls. Throws Error on a non-finite value, naming its light index.
void append_residual_row(const float* residual, int lights, int max_entries, float threshold,
                         ResidualRows& rows, std::vector<int>& scratch);

// All rows of a dense residual (rows x lights), as above.
ResidualRows select_residual(const RowMatrixF& residual, int max_entries, float threshold);

}  // namespace relume
