// Re-expresses a compressed field's clusters in orthonormal, mutually aligned bases without
// changing what it reconstructs: per cluster, F^k = U S V^T (thin SVD), so W F^k = (W U S) V^T;
// then V^T is turned by the orthogonal matrix O_k (orthogonal Procrustes) that brings it closest
// to one shared reference basis G, the dominant subspace of all clusters' bases weighted by their
// sizes. Afterwards
//   - the error a weight change makes is that change in L2 (orthonormal rows), so one
//     quantization step means the same absolute error in every cluster, and
//   - weights mean nearly the same in neighbouring clusters (aligned bases), so the weights of
//     neighbouring pixels stay similar across cluster borders and predict each other.
#pragma once

#include <Eigen/Dense>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// The aligned bases of a field and how each cluster's weights change with them.
struct BasisAlignment {
  std::vector<float> bases;              // the aligned F
  std::vector<std::vector<int>> active;  // per cluster its used terms before (empty: no change)
  std::vector<Eigen::MatrixXd> weight_transform;  // per cluster: W' (used terms first) = W_active T
};

// The alignment of `field`'s bases, the reference weighted by `cluster_sizes` (stored rows per
// cluster): from the bases alone, so that a field held in strips (its stored rows on disk) is
// aligned strip by strip with apply_basis_alignment.
BasisAlignment cluster_basis_alignment(const CompressedField& field,
                                       const std::vector<std::size_t>& cluster_sizes);

// Sets `field`'s bases to the aligned ones and transforms the weights of its stored rows.
void apply_basis_alignment(const BasisAlignment& alignment, CompressedField& field);

// Both in place, the cluster sizes counted from `field`; the product W F^k of every row changes only by float rounding. Clusters whose basis
// has fewer independent rows than terms keep zero weights for the missing directions. Only a
// cluster's used basis rows (not all zero, model/cluster_terms.hpp) are aligned, to the
// reference's leading directions; they move to the cluster's first slots, and unused rows and
// their weights stay zero.
void align_cluster_bases(CompressedField& field);

}  // namespace relume
