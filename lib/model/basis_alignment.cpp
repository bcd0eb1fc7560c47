// Implementation of the orthonormal, aligned re-expression of cluster bases.
#include "model/basis_alignment.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <vector>

namespace relume {
namespace {

using MatrixD = Eigen::MatrixXd;

MatrixD cluster_basis(const CompressedField& field, int k) {
  MatrixD basis(field.terms, field.lights);
  const float* f = field.basis(k);
  for (int j = 0; j < field.terms; ++j)
    for (int i = 0; i < field.lights; ++i) basis(j, i) = f[std::size_t(j) * field.lights + i];
  return basis;
}

}  // namespace

void align_cluster_bases(CompressedField& field) {
  const int t = field.terms, m = field.lights, K = field.clusters;
  if (t == 0 || K == 0 || t > m) return;
  std::vector<std::size_t> sizes(K, 0);
  for (std::uint32_t k : field.cluster) ++sizes[k];

  // Each cluster's orthonormal rows V^T and the weight transform U S.
  std::vector<MatrixD> rows(K), weight_transform(K);
  for (int k = 0; k < K; ++k) {
    const Eigen::JacobiSVD<MatrixD> svd(cluster_basis(field, k),
                                        Eigen::ComputeThinU | Eigen::ComputeThinV);
    // V has t orthonormal columns even when the basis is rank deficient (the extra directions
    // have singular value 0, so no weight uses them).
    rows[k] = svd.matrixV().leftCols(t).transpose();
    weight_transform[k] = svd.matrixU() * svd.singularValues().asDiagonal();
  }

  // The reference: the dominant t-dimensional subspace of the clusters' rows, weighted by size.
  MatrixD stacked(std::size_t(K) * t, m);
  for (int k = 0; k < K; ++k)
    stacked.middleRows(Eigen::Index(k) * t, t) = std::sqrt(double(sizes[k])) * rows[k];
  const Eigen::BDCSVD<MatrixD> reference_svd(stacked, Eigen::ComputeThinV);
  const MatrixD reference = reference_svd.matrixV()
                                .leftCols(std::min(t, int(reference_svd.matrixV().cols())))
                                .transpose();

  for (int k = 0; k < K; ++k) {
    // O = argmin ||O V^T - G||_F over orthogonal O: O = P Q^T from the SVD of G V = P S Q^T.
    MatrixD rotation = MatrixD::Identity(t, t);
    if (reference.rows() == t) {
      const Eigen::JacobiSVD<MatrixD> procrustes(reference * rows[k].transpose(),
                                                 Eigen::ComputeFullU | Eigen::ComputeFullV);
      rotation = procrustes.matrixU() * procrustes.matrixV().transpose();
    }
    const MatrixD aligned = rotation * rows[k];
    // W' = W (U S) O^T, so that W' (O V^T) = W U S V^T = W F.
    weight_transform[k] = weight_transform[k] * rotation.transpose();
    float* f = field.bases.data() + std::size_t(k) * t * m;
    for (int j = 0; j < t; ++j)
      for (int i = 0; i < m; ++i) f[std::size_t(j) * m + i] = float(aligned(j, i));
  }
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const Eigen::RowVectorXd w =
        field.weights.row(Eigen::Index(r)).cast<double>() * weight_transform[field.cluster[r]];
    field.weights.row(Eigen::Index(r)) = w.cast<float>();
  }
}

}  // namespace relume
