// Terms per cluster: a cluster of dim or simple functions needs fewer basis functions than one of
// bright, glossy ones (issue 11, "model only what the scene requires"). A compressed field keeps
// one `terms` for all clusters; a term that cluster k does not use has an all-zero basis row
// F^k[j] and zero weights, so it adds nothing to any reconstruction, and the container (format
// version 3) stores no weight for it.
//
// drop_unneeded_terms chooses those terms by rate against distortion: each cluster's basis is
// re-expressed in orthonormal rows (exactly: W F^k is unchanged), the Eq. 16 error each row adds
// is measured exactly against the original field, and the rows that cost the least error per
// stored byte are dropped while the error stays within a relative budget.
#pragma once

#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// Whether basis row F^k[j] holds a non-zero value: flags[k * terms + j].
std::vector<std::uint8_t> used_basis_rows(const CompressedField& field);

// The number of used basis rows of each cluster.
std::vector<int> terms_per_cluster(const CompressedField& field);

struct TermChoice {
  std::vector<int> cluster_terms;  // terms each cluster keeps
  double error_all_terms = 0;      // Eq. 16 over the stored rows before
  double error_chosen = 0;         // and after (exact, not estimated)
  std::size_t dropped = 0;         // basis rows dropped
};

// In place: every cluster's used basis rows become orthonormal and ordered by the error they
// remove, the kept ones first; then the rows whose removal adds the least Eq. 16 error per byte
// they cost (the cluster's weights plus the basis row) are zeroed with their weights while the
// error over the stored rows rises by at most `relative_increase` (0: the field is left as it
// is). The residual is kept as it is. `original` is the field `field` was compressed from.
TermChoice drop_unneeded_terms(const ReflectanceField& original, CompressedField& field,
                               double relative_increase, unsigned threads);

}  // namespace relume
