// The leading right singular vectors (compress/leading_subspace.hpp) against Eigen's exact SVD in
// double: the energy the subspace captures, orthonormality, and the rank-deficient and empty
// cases, for the Gram path and the subspace iteration alike.
#include "compress/leading_subspace.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

namespace relume {
namespace {

// Rows of a rank-`rank` matrix with singular values decaying by `decay`, plus `noise`.
RowMatrixF planted(int rows, int columns, int rank, double decay, double noise) {
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd left(rows, rank), right(rank, columns);
  for (Eigen::Index i = 0; i < left.size(); ++i) left.data()[i] = normal(random);
  for (Eigen::Index i = 0; i < right.size(); ++i) right.data()[i] = normal(random);
  for (int k = 0; k < rank; ++k) left.col(k) *= std::pow(decay, k);
  Eigen::MatrixXd X = left * right;
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] += noise * normal(random);
  return X.cast<float>();
}

double captured_energy(const RowMatrixF& X, const Eigen::MatrixXd& rows) {
  return (X.cast<double>() * rows.transpose()).squaredNorm();
}

double best_energy(const RowMatrixF& X, int terms) {
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(X.cast<double>());
  return svd.singularValues().head(terms).squaredNorm();
}

double orthonormality_error(const Eigen::MatrixXd& rows) {
  const Eigen::Index t = rows.rows();
  return (rows * rows.transpose() - Eigen::MatrixXd::Identity(t, t)).cwiseAbs().maxCoeff();
}

struct Case {
  const char* name;
  int rows, columns, rank;
  double decay, noise;
  SubspaceMethod method;
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

class LeadingSubspace : public testing::TestWithParam<Case> {};

TEST_P(LeadingSubspace, CapturesTheEnergyOfTheExactSvd) {
  const Case c = GetParam();
  const RowMatrixF X = planted(c.rows, c.columns, c.rank, c.decay, c.noise);
  for (const int terms : {1, 4, 12}) {
    const Eigen::MatrixXd V = leading_right_singular_vectors(X, terms, c.method);
    ASSERT_EQ(V.rows(), terms);
    ASSERT_EQ(V.cols(), c.columns);
    EXPECT_LT(orthonormality_error(V), 1e-9) << c.name << " terms " << terms;
    const double best = best_energy(X, terms);
    EXPECT_NEAR(captured_energy(X, V), best, 2e-6 * best) << c.name << " terms " << terms;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, LeadingSubspace,
    testing::Values(
        // A clear gap after the planted rank, then a slowly decaying spectrum with no gap.
        Case{"tall_gram", 1500, 300, 6, 0.7, 0.01, SubspaceMethod::gram},
        Case{"tall_iteration", 1500, 300, 6, 0.7, 0.01, SubspaceMethod::subspace_iteration},
        Case{"wide_gram", 40, 700, 30, 0.95, 0.01, SubspaceMethod::gram},
        Case{"wide_iteration", 40, 700, 30, 0.95, 0.01, SubspaceMethod::subspace_iteration},
        Case{"no_gap_iteration", 800, 400, 60, 0.98, 0.05, SubspaceMethod::subspace_iteration},
        Case{"automatic", 1200, 600, 8, 0.8, 0.02, SubspaceMethod::automatic}),
    [](const testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(LeadingSubspaceEdges, FewerRowsThanTermsAreCompletedOrthonormally) {
  const RowMatrixF X = planted(2, 50, 2, 1.0, 0.0);
  for (const auto method : {SubspaceMethod::gram, SubspaceMethod::subspace_iteration}) {
    const Eigen::MatrixXd V = leading_right_singular_vectors(X, 5, method);
    ASSERT_EQ(V.rows(), 5);
    EXPECT_LT(orthonormality_error(V), 1e-9);
    // The first two rows span X's rows: the whole energy is captured.
    const double energy = X.cast<double>().squaredNorm();
    EXPECT_NEAR(captured_energy(X, V.topRows(2)), energy, 1e-6 * energy);
  }
}

TEST(LeadingSubspaceWarmStart, AnyStartGivesTheBestSubspace) {
  const RowMatrixF X = planted(900, 350, 10, 0.8, 0.02);
  const int terms = 4;
  const double best = best_energy(X, terms);
  const Eigen::MatrixXd exact = leading_right_singular_vectors(X, terms, SubspaceMethod::gram);
  std::mt19937_64 random(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd perturbed = exact;
  for (Eigen::Index i = 0; i < perturbed.size(); ++i) perturbed.data()[i] += 0.3 * normal(random);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(terms, X.cols());
  const std::vector<const Eigen::MatrixXd*> starts{&exact, &perturbed, &zero};
  for (const Eigen::MatrixXd* start : starts) {
    const RowMatrixF rows = start->cast<float>();
    const Eigen::MatrixXd V =
        leading_right_singular_vectors(X, terms, SubspaceMethod::subspace_iteration, rows.data());
    EXPECT_LT(orthonormality_error(V), 1e-9);
    EXPECT_NEAR(captured_energy(X, V), best, 2e-6 * best);
  }
}

TEST(LeadingSubspaceEdges, NoRowsGiveAnOrthonormalSet) {
  const RowMatrixF X(0, 20);
  const Eigen::MatrixXd V = leading_right_singular_vectors(X, 3);
  ASSERT_EQ(V.rows(), 3);
  EXPECT_LT(orthonormality_error(V), 1e-12);
}

TEST(LeadingSubspaceEdges, ZeroRowsGiveAnOrthonormalSet) {
  const RowMatrixF X = RowMatrixF::Zero(30, 20);
  for (const auto method : {SubspaceMethod::gram, SubspaceMethod::subspace_iteration})
    EXPECT_LT(orthonormality_error(leading_right_singular_vectors(X, 4, method)), 1e-12);
}

}  // namespace
}  // namespace relume
