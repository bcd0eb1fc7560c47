// Tests of the alternating L1 factorization, after the paper's own experiments: planted recovery
// of a sparse residual (R = W F + E with random W, F and a controlled fraction of non-zeros in E)
// against an L2 (SVD) factorization, the extremes the header documents, and `relume factor`
// round trips through .npy files.
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <relume/error.hpp>

#include "field/npy.hpp"
#include "l1/factorization.hpp"
#include "l1/planted_matrix.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

void expect_finite_and_consistent(const Eigen::MatrixXd& R, const L1Factorization& f, int terms) {
  ASSERT_EQ(f.W.rows(), R.rows());
  ASSERT_EQ(f.W.cols(), terms);
  ASSERT_EQ(f.F.rows(), terms);
  ASSERT_EQ(f.F.cols(), R.cols());
  EXPECT_TRUE(f.W.allFinite());
  EXPECT_TRUE(f.F.allFinite());
  EXPECT_TRUE(f.E.allFinite());
  // R = W F + E up to the zeroed entries (at most 1e-9 of each row's largest |R|).
  for (Eigen::Index p = 0; p < R.rows(); ++p)
    EXPECT_LE((R.row(p) - f.W.row(p) * f.F - f.E.row(p)).cwiseAbs().maxCoeff(),
              1e-9 * R.row(p).cwiseAbs().maxCoeff() + 1e-300)
        << "row " << p;
  EXPECT_FALSE(f.objective_per_iteration.empty());
}

TEST(L1Factorization, RecoversPlantedSparseResidualWhereSvdDoesNot) {
  const PlantedMatrix p = make_planted_matrix(200, 200, 4, 0.05, 21);
  FactorizationOptions options;  // lp-dual, random basis start
  const L1Factorization f = factorize_l1(p.R, 4, options);
  expect_finite_and_consistent(p.R, f, 4);
  const SupportMatch l1 = compare_support(f.E, p.E, 1e-6);
  EXPECT_GE(l1.precision, 0.99);
  EXPECT_GE(l1.recall, 0.99);
  EXPECT_LT((f.E - p.E).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(f.objective_per_iteration.back(), p.E.lpNorm<1>(), 1e-6 * p.E.lpNorm<1>());
  // Exact solves never raise the objective (beyond round-off).
  for (std::size_t k = 1; k < f.objective_per_iteration.size(); ++k)
    EXPECT_LE(f.objective_per_iteration[k], f.objective_per_iteration[k - 1] * (1 + 1e-9));
  // L2: the rank-4 truncated SVD spreads the outliers over every entry.
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(p.R, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::MatrixXd low_rank = svd.matrixU().leftCols(4) *
                                   svd.singularValues().head(4).asDiagonal() *
                                   svd.matrixV().leftCols(4).transpose();
  const SupportMatch l2 = compare_support(p.R - low_rank, p.E, 1e-6);
  EXPECT_LT(l2.precision, 0.1);
  // ... and gets the residual values wrong everywhere, where L1 gets them to round-off.
  const double l2_error = (p.R - low_rank - p.E).cwiseAbs().maxCoeff();
  EXPECT_GT(l2_error, 0.05);
  std::printf(
      "planted 200 x 200, t = 4, 5%%: L1 precision %.4f recall %.4f, max |E error| %.2e; "
      "SVD precision %.4f, max |E error| %.3f\n",
      l1.precision, l1.recall, (f.E - p.E).cwiseAbs().maxCoeff(), l2.precision, l2_error);
}

TEST(L1Factorization, RecoversSupportAtEveryPlantedDensity) {
  for (double density : {0.01, 0.10, 0.20}) {
    const PlantedMatrix p = make_planted_matrix(80, 80, 3, density, 22);
    FactorizationOptions options;
    options.relative_tolerance = 1e-9;
    const L1Factorization f = factorize_l1(p.R, 3, options);
    expect_finite_and_consistent(p.R, f, 3);
    const SupportMatch match = compare_support(f.E, p.E, 1e-6);
    EXPECT_GE(match.precision, 0.99) << density;
    EXPECT_GE(match.recall, 0.99) << density;
  }
}

TEST(L1Factorization, BothLpFormsReachTheSameObjective) {
  const PlantedMatrix p = make_planted_matrix(60, 50, 3, 0.1, 23);
  FactorizationOptions options;
  options.relative_tolerance = 1e-10;
  options.l1.method = L1Method::lp_primal;
  const L1Factorization primal = factorize_l1(p.R, 3, options);
  options.l1.method = L1Method::lp_dual;
  const L1Factorization dual = factorize_l1(p.R, 3, options);
  EXPECT_NEAR(primal.objective_per_iteration.back(), dual.objective_per_iteration.back(),
              1e-6 * dual.objective_per_iteration.back());
}

TEST(L1Factorization, ApproximateSolversComeCloseAndStopWhenTheObjectiveRises) {
  const PlantedMatrix p = make_planted_matrix(60, 60, 3, 0.1, 24);
  FactorizationOptions options;
  const double exact = factorize_l1(p.R, 3, options).objective_per_iteration.back();
  for (L1Method method : {L1Method::huber, L1Method::irls}) {
    options.l1.method = method;
    const L1Factorization f = factorize_l1(p.R, 3, options);
    expect_finite_and_consistent(p.R, f, 3);
    const double best =
        *std::min_element(f.objective_per_iteration.begin(), f.objective_per_iteration.end());
    EXPECT_NEAR(f.E.lpNorm<1>(), best, 1e-6 * best) << "returns the best iterate";
    EXPECT_LT(best, exact * 1.01) << to_string(method);
  }
}

TEST(L1Factorization, SameSeedSameResultAndIterationCallback) {
  const PlantedMatrix p = make_planted_matrix(40, 30, 2, 0.1, 25);
  FactorizationOptions options;
  options.threads = 1;
  options.max_iterations = 3;
  options.relative_tolerance = 0;
  std::vector<double> reported;
  options.on_iteration = [&](int iteration, double objective) {
    EXPECT_EQ(iteration, int(reported.size()) + 1);
    reported.push_back(objective);
  };
  const L1Factorization a = factorize_l1(p.R, 2, options);
  EXPECT_EQ(reported, a.objective_per_iteration);
  EXPECT_LE(a.objective_per_iteration.size(), 3u);
  options.on_iteration = nullptr;
  const L1Factorization b = factorize_l1(p.R, 2, options);
  EXPECT_EQ(a.W, b.W);
  EXPECT_EQ(a.F, b.F);
  options.seed = 99;
  options.init = FactorizationInit::random_weights;
  EXPECT_NE(factorize_l1(p.R, 2, options).W, a.W);
}

TEST(L1Factorization, ExtremesGiveFiniteDocumentedResults) {
  const PlantedMatrix p = make_planted_matrix(30, 12, 2, 0.1, 26);
  for (L1Method method :
       {L1Method::lp_primal, L1Method::lp_dual, L1Method::huber, L1Method::irls}) {
    SCOPED_TRACE(to_string(method));
    FactorizationOptions options;
    options.l1.method = method;
    // terms = columns: every row is fitted exactly, no residual; more terms explain nothing
    // more and are refused (they would only size W and F).
    const L1Factorization wide = factorize_l1(p.R, 12, options);
    expect_finite_and_consistent(p.R, wide, 12);
    EXPECT_LT(wide.E.cwiseAbs().maxCoeff(), 1e-6 * p.R.cwiseAbs().maxCoeff());
    EXPECT_THROW(factorize_l1(p.R, 13, options), Error);
    // One term.
    expect_finite_and_consistent(p.R, factorize_l1(p.R, 1, options), 1);
    // Rank-deficient truth (rank 2, 4 terms): a basis row may become redundant, nothing breaks.
    expect_finite_and_consistent(p.R, factorize_l1(p.R, 4, options), 4);
    // All-zero rows, rows scaled by 1e-8 and 1e8, duplicate rows.
    Eigen::MatrixXd R = p.R;
    R.row(0).setZero();
    R.row(1) *= 1e-8;
    R.row(2) *= 1e8;
    R.row(3) = R.row(4);
    const L1Factorization f = factorize_l1(R, 2, options);
    expect_finite_and_consistent(R, f, 2);
    EXPECT_EQ(f.W.row(0), Eigen::RowVectorXd::Zero(2)) << "zero row gets zero weights";
    EXPECT_EQ(f.E.row(0), Eigen::RowVectorXd::Zero(12));
    EXPECT_LT((f.W.row(3) * f.F - f.W.row(4) * f.F).cwiseAbs().maxCoeff(),
              1e-6 * R.row(4).cwiseAbs().maxCoeff())
        << "duplicate rows get the same fit";
  }
}

TEST(L1Factorization, RefusesBadInput) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Ones(4, 3);
  EXPECT_THROW(factorize_l1(R, 0, {}), Error);
  R(2, 1) = NAN;
  try {
    factorize_l1(R, 1, {});
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("row 2, column 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_factorization_init("kmeans"), Error);
}

TEST(FactorCommand, RoundTripsNpyFilesInTheInputDtype) {
  testing::TempDir dir;
  const PlantedMatrix p = make_planted_matrix(40, 30, 2, 0.05, 27);
  for (NpyDtype dtype : {NpyDtype::float32, NpyDtype::float64}) {
    const Eigen::MatrixXd R = dtype == NpyDtype::float32 ? p.R.cast<float>().cast<double>() : p.R;
    write_npy_matrix(dir / "r.npy", R, dtype);
    const auto result =
        testing::run_relume("-y factor '" + (dir / "r.npy").string() + "' -t 2 -o '" +
                            (dir / "out").string() + "' --threads 2");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("iteration 1: L1 objective"), std::string::npos) << result.output;
    const NpyMatrix W = read_npy_matrix(dir / "out_W.npy");
    const NpyMatrix F = read_npy_matrix(dir / "out_F.npy");
    const NpyMatrix E = read_npy_matrix(dir / "out_E.npy");
    EXPECT_EQ(W.dtype, dtype);
    EXPECT_EQ(E.dtype, dtype);
    ASSERT_EQ(W.values.rows(), 40);
    ASSERT_EQ(W.values.cols(), 2);
    ASSERT_EQ(F.values.rows(), 2);
    ASSERT_EQ(F.values.cols(), 30);
    const double tolerance = dtype == NpyDtype::float32 ? 1e-4 : 1e-9;
    EXPECT_LT((R - W.values * F.values - E.values).cwiseAbs().maxCoeff(),
              tolerance * R.cwiseAbs().maxCoeff());
    const SupportMatch match = compare_support(E.values, p.E, 1e-3);
    EXPECT_GE(match.precision, 0.99);
    EXPECT_GE(match.recall, 0.99);
    // The default residual threshold follows the dtype: float32 rounding is not kept as residual.
    const SupportMatch stored = compare_support(E.values, p.E, 0.0);
    EXPECT_GE(stored.precision, 0.99) << (dtype == NpyDtype::float32 ? "float32" : "float64");
  }
}

TEST(FactorCommand, ReadsAFileWrittenByNumpy) {
  // np.save of np.array([[1.5, -2.0, 3.25], [0.0, 1e-8, -7e5]], dtype=np.float32).T.copy() would
  // do as well; this is the float32 2 x 3 file NumPy 1.24 writes, byte for byte.
  const std::string header =
      "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }" + std::string(58, ' ') + "\n";
  std::string bytes = std::string("\x93NUMPY\x01\x00v\x00", 10) + header;
  for (float value : {1.5f, -2.0f, 3.25f, 0.0f, 1e-8f, -7e5f})
    bytes.append(reinterpret_cast<const char*>(&value), 4);
  ASSERT_EQ(bytes.size(), 152u);
  testing::TempDir dir;
  {
    std::ofstream out(dir / "numpy.npy", std::ios::binary);
    out << bytes;
  }
  const auto result = testing::run_relume("factor '" + (dir / "numpy.npy").string() +
                                          "' -t 1 --solver lp -o '" + (dir / "x").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(read_npy_matrix(dir / "x_E.npy").dtype, NpyDtype::float32);
}

TEST(FactorCommand, ReportsMalformedInputAndBadOptions) {
  testing::TempDir dir;
  {
    std::ofstream out(dir / "bad.npy", std::ios::binary);
    out << "\x93NUMPY\x01\x00\x10\x00{'descr': '<f8'";
  }
  auto result = testing::run_relume("factor '" + (dir / "bad.npy").string() + "' -t 2 -o '" +
                                    (dir / "o").string() + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("bad.npy"), std::string::npos) << result.output;
  write_npy_matrix(dir / "ok.npy", Eigen::MatrixXd::Ones(3, 3), NpyDtype::float64);
  result = testing::run_relume("factor '" + (dir / "ok.npy").string() +
                               "' -t 2 --solver simplex -o '" + (dir / "o").string() + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("unknown L1 solver 'simplex'"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "o_W.npy"));
}

}  // namespace
}  // namespace relume
