// Clustered PCA (Sloan, Hall, Hart, Snyder, "Clustered Principal Components for Precomputed
// Radiance Transfer", SIGGRAPH 2003), the method the paper compares with, written into the same
// ClusterModel as the L1 method so that the same residual selection, container and kernels serve
// it. Each cluster is an affine subspace, a mean plus principal components, fitted in least
// squares; each row goes to the cluster with the smallest least-squares reconstruction error;
// fit and reassignment alternate until few rows move.
//
// It gets relume's own advantages, since a baseline is only honest when it is as strong as it can
// be: the rows are the unit-norm rows the L1 method clusters (so the least-squares error is the
// per-function error of paper Eq. 16) and the start is the L1 method's seeding (k-means++ for
// subspaces and its least-squares rounds, lib/compress/cluster_seeding.hpp).
//
// How the mean is stored. The container holds t basis rows per cluster and t weights per row
// (W F + E). A mean and t - 1 components span a t-dimensional linear subspace that contains the
// affine one, so they are stored as an orthonormal basis of that span, and every row's t weights
// are its least-squares projection onto it: the affine reconstruction (mean weight 1) is one
// point of the span, so the stored error is never above the affine error, and the stored model
// has exactly the L1 method's shape and byte count at equal --terms. Without centring
// (PcaCentering::none) the cluster is the best t-dimensional linear subspace (t components, no
// mean), which at equal stored terms is at least as good for a fixed clustering.
#pragma once

#include <cstdint>
#include <string>

#include "compress/cluster_iterations.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

enum class PcaCentering : std::uint8_t {
  mean,  // Sloan et al.: a mean plus terms - 1 principal components per cluster
  none,  // terms principal components about the origin (k-subspaces)
};

// "mean" or "none"; throws Error naming the bad text.
PcaCentering parse_pca_centering(const std::string& text);
std::string to_string(PcaCentering centering);

struct ClusteredPcaOptions {
  PcaCentering centering = PcaCentering::none;
  // Fit + reassignment rounds after the seeding (they stop once settled).
  int iterations = compress_defaults().pca_iterations;
};

// Clusters `rows` by clustered PCA. From `clustering` it takes the clusters, terms, seeding
// settings, the minimum cluster size (smaller clusters are dissolved into their rows' next-best
// clusters, as the L1 method does), the settle fraction, the threads and quiet. The records in
// `trace` hold the L1 norm of the least-squares residual (comparable with the L1 method's
// objective) and the time of each step. The returned model's bases are orthonormal and its
// weights are least-squares projections.
ClusterModel cluster_rows_pca(const WorkingRows& rows, const ClusteringOptions& clustering,
                              const ClusteredPcaOptions& options, ClusteringTrace& trace);

}  // namespace relume
