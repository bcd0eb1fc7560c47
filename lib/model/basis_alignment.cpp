// Implementation of the orthonormal, aligned re-expression of cluster bases.
#include "model/basis_alignment.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <vector>

#include "model/cluster_terms.hpp"

namespace relume {
namespace {

using MatrixD = Eigen::MatrixXd;

// Cluster k's used basis rows (those not all zero), as rows of a matrix.
MatrixD used_rows(const CompressedField& field, int k, const std::vector<int>& active) {
  MatrixD basis(Eigen::Index(active.size()), field.lights);
  const float* f = field.basis(k);
  for (std::size_t q = 0; q < active.size(); ++q)
    for (int i = 0; i < field.lights; ++i)
      basis(Eigen::Index(q), i) = f[std::size_t(active[q]) * field.lights + i];
  return basis;
}

}  // namespace

BasisAlignment cluster_basis_alignment(const CompressedField& field,
                                       const std::vector<std::size_t>& sizes) {
  const int t = field.terms, m = field.lights, K = field.clusters;
  BasisAlignment alignment;
  alignment.bases = field.bases;
  if (t == 0 || K == 0 || t > m) return alignment;
  const std::vector<std::uint8_t> used = used_basis_rows(field);

  // Each cluster's used rows made orthonormal, V^T, and the weight transform U S.
  std::vector<std::vector<int>>& active = alignment.active;
  std::vector<MatrixD>& weight_transform = alignment.weight_transform;
  active.resize(std::size_t(K));
  weight_transform.resize(std::size_t(K));
  std::vector<MatrixD> rows(K);
  Eigen::Index stacked_rows = 0;
  for (int k = 0; k < K; ++k) {
    for (int j = 0; j < t; ++j)
      if (used[std::size_t(k) * t + j]) active[k].push_back(j);
    if (active[k].empty()) continue;
    const Eigen::JacobiSVD<MatrixD> svd(used_rows(field, k, active[k]),
                                        Eigen::ComputeThinU | Eigen::ComputeThinV);
    // V has as many orthonormal columns as used rows even when they are dependent (the extra
    // directions have singular value 0, so no weight uses them).
    rows[k] = svd.matrixV().transpose();
    weight_transform[k] = svd.matrixU() * svd.singularValues().asDiagonal();
    stacked_rows += rows[k].rows();
  }
  if (stacked_rows == 0) {
    alignment.active.clear();  // nothing to align: the field stays as it is
    return alignment;
  }

  // The reference: the dominant t-dimensional subspace of the clusters' rows, weighted by size.
  MatrixD stacked(stacked_rows, m);
  Eigen::Index at = 0;
  for (int k = 0; k < K; ++k) {
    stacked.middleRows(at, rows[k].rows()) = std::sqrt(double(sizes[k])) * rows[k];
    at += rows[k].rows();
  }
  const Eigen::BDCSVD<MatrixD> reference_svd(stacked, Eigen::ComputeThinV);
  const MatrixD reference = reference_svd.matrixV()
                                .leftCols(std::min(t, int(reference_svd.matrixV().cols())))
                                .transpose();

  for (int k = 0; k < K; ++k) {
    const Eigen::Index a = rows[k].rows();
    if (a == 0) continue;
    // O = argmin ||O V^T - G||_F over orthogonal O, G the reference's first `a` rows: O = P Q^T
    // from the SVD of G V = P S Q^T.
    MatrixD rotation = MatrixD::Identity(a, a);
    if (reference.rows() >= a) {
      const Eigen::JacobiSVD<MatrixD> procrustes(reference.topRows(a) * rows[k].transpose(),
                                                 Eigen::ComputeFullU | Eigen::ComputeFullV);
      rotation = procrustes.matrixU() * procrustes.matrixV().transpose();
    }
    const MatrixD aligned = rotation * rows[k];
    // W' = W (U S) O^T, so that W' (O V^T) = W U S V^T = W F; the used rows move to the front.
    weight_transform[k] = weight_transform[k] * rotation.transpose();
    float* f = alignment.bases.data() + std::size_t(k) * t * m;
    std::fill(f, f + std::size_t(t) * m, 0.0f);
    for (Eigen::Index q = 0; q < a; ++q)
      for (int i = 0; i < m; ++i) f[std::size_t(q) * m + i] = float(aligned(q, i));
  }
  return alignment;
}

void apply_basis_alignment(const BasisAlignment& alignment, CompressedField& field) {
  if (alignment.active.empty()) return;
  field.bases = alignment.bases;
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t k = field.cluster[r];
    const std::vector<int>& of = alignment.active[k];
    Eigen::RowVectorXd w(Eigen::Index(of.size()));
    for (std::size_t q = 0; q < of.size(); ++q)
      w(Eigen::Index(q)) = field.weights(Eigen::Index(r), of[q]);
    auto row = field.weights.row(Eigen::Index(r));
    row.setZero();
    if (of.empty()) continue;
    const Eigen::RowVectorXd aligned = w * alignment.weight_transform[k];
    for (Eigen::Index q = 0; q < aligned.size(); ++q) row(q) = float(aligned(q));
  }
}

void align_cluster_bases(CompressedField& field) {
  std::vector<std::size_t> sizes(std::size_t(std::max(field.clusters, 0)), 0);
  for (std::uint32_t k : field.cluster) ++sizes[k];
  apply_basis_alignment(cluster_basis_alignment(field, sizes), field);
}

}  // namespace relume
