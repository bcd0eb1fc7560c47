// Tests of the L1 (least absolute deviations) regression solvers: both exact LP forms against a
// brute-force vertex search and each other, the Huber QP's approach to the L1 optimum as gamma
// shrinks, the IRLS gap, the non-negative residual, the batched solve, degenerate inputs, and a
// captured problem on which GLPK's default ratio test never finishes.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <cmath>
#include <fstream>
#include <random>
#include <relume/error.hpp>
#include <string>

#include "l1/regression.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

const L1Method kAllMethods[] = {L1Method::lp_primal, L1Method::lp_dual, L1Method::huber,
                                L1Method::irls};

L1Options options_for(L1Method method) {
  L1Options options;
  options.method = method;
  return options;
}

Eigen::MatrixXd gaussian(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  return Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return normal(random); });
}

// b = A x_true + outliers on a `fraction` of the observations.
Eigen::VectorXd planted_rhs(const Eigen::MatrixXd& design, const Eigen::VectorXd& x_true,
                            double fraction, std::mt19937_64& random) {
  std::uniform_real_distribution<double> uniform;
  Eigen::VectorXd rhs = design * x_true;
  for (Eigen::Index i = 0; i < rhs.size(); ++i)
    if (uniform(random) < fraction)
      rhs[i] += (uniform(random) < 0.5 ? -1 : 1) * (1 + 4 * uniform(random));
  return rhs;
}

// The exact L1 optimum by brute force: an optimum interpolates `unknowns` observations (for a
// design of full column rank), so try every such subset.
double brute_force_l1(const Eigen::MatrixXd& design, const Eigen::VectorXd& rhs) {
  const int m = static_cast<int>(design.rows());
  const int t = static_cast<int>(design.cols());
  double best = rhs.lpNorm<1>();
  std::vector<int> subset(t);
  for (int k = 0; k < t; ++k) subset[k] = k;
  while (true) {
    Eigen::MatrixXd rows(t, t);
    Eigen::VectorXd values(t);
    for (int k = 0; k < t; ++k) {
      rows.row(k) = design.row(subset[k]);
      values[k] = rhs[subset[k]];
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(rows);
    if (lu.isInvertible()) best = std::min(best, (rhs - design * lu.solve(values)).lpNorm<1>());
    int k = t - 1;
    while (k >= 0 && subset[k] == m - t + k) --k;
    if (k < 0) break;
    ++subset[k];
    for (int j = k + 1; j < t; ++j) subset[j] = subset[j - 1] + 1;
  }
  return best;
}

TEST(L1Regression, ParsesMethodNames) {
  for (L1Method method : kAllMethods) EXPECT_EQ(parse_l1_method(to_string(method)), method);
  EXPECT_EQ(parse_l1_method("lp"), L1Method::lp_primal);
  EXPECT_THROW(parse_l1_method("simplex"), Error);
}

TEST(L1Regression, ExactFormsMatchBruteForceOptimum) {
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::MatrixXd design = gaussian(25, 3, random);
    const Eigen::VectorXd rhs = gaussian(25, 1, random);
    const double optimum = brute_force_l1(design, rhs);
    for (L1Method method : {L1Method::lp_primal, L1Method::lp_dual}) {
      LadSolver solver(design, options_for(method));
      double objective = 0;
      const Eigen::VectorXd x = solver.solve(rhs, &objective);
      EXPECT_NEAR(objective, optimum, 1e-9 * optimum) << to_string(method);
      EXPECT_NEAR((rhs - design * x).lpNorm<1>(), objective, 1e-12 * optimum);
    }
  }
}

TEST(L1Regression, MedianOfOneColumnDesign) {
  const Eigen::MatrixXd design = Eigen::MatrixXd::Ones(5, 1);
  Eigen::VectorXd rhs(5);
  rhs << 3, -1, 10, 2, 7;
  for (L1Method method : {L1Method::lp_primal, L1Method::lp_dual}) {
    LadSolver solver(design, options_for(method));
    EXPECT_NEAR(solver.solve(rhs)[0], 3.0, 1e-12) << to_string(method);
  }
}

TEST(L1Regression, RecoversPlantedWeightsDespiteOutliers) {
  std::mt19937_64 random(5);
  const Eigen::MatrixXd design = gaussian(200, 4, random);
  const Eigen::VectorXd x_true = gaussian(4, 1, random);
  const Eigen::VectorXd rhs = planted_rhs(design, x_true, 0.1, random);
  for (L1Method method : {L1Method::lp_primal, L1Method::lp_dual}) {
    LadSolver solver(design, options_for(method));
    EXPECT_LT((solver.solve(rhs) - x_true).norm(), 1e-9) << to_string(method);
  }
  // Least squares is pulled off by the outliers.
  EXPECT_GT((design.colPivHouseholderQr().solve(rhs) - x_true).norm(), 1e-2);
}

TEST(L1Regression, PrimalAndWarmStartedDualAgreeOverManyRightHandSides) {
  std::mt19937_64 random(7);
  const Eigen::MatrixXd design = gaussian(120, 5, random);
  const Eigen::MatrixXd rhs = gaussian(120, 60, random);
  LadSolver primal(design, options_for(L1Method::lp_primal));
  LadSolver dual(design, options_for(L1Method::lp_dual));
  for (Eigen::Index k = 0; k < rhs.cols(); ++k) {
    double primal_objective = 0, dual_objective = 0;
    primal.solve(rhs.col(k), &primal_objective);
    dual.solve(rhs.col(k), &dual_objective);
    EXPECT_NEAR(primal_objective, dual_objective, 1e-6 * primal_objective) << "column " << k;
  }
}

TEST(L1Regression, ProblemWhereHarrisRatioTestStallsIsSolvedToTheOptimum) {
  std::ifstream file(testing::source_dir() / "tests/l1/data/harris_stall_lp.txt");
  ASSERT_TRUE(file) << "tests/l1/data/harris_stall_lp.txt";
  std::string comment;
  while (file.peek() == '#') std::getline(file, comment);
  Eigen::Index rows = 0, cols = 0;
  file >> rows >> cols;
  ASSERT_EQ(rows, 50);
  ASSERT_EQ(cols, 3);
  Eigen::MatrixXd design(rows, cols);
  Eigen::VectorXd rhs(rows);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) file >> design(i, j);
  for (Eigen::Index i = 0; i < rows; ++i) file >> rhs[i];
  ASSERT_TRUE(file) << "the file ended early";
  const double optimum = brute_force_l1(design, rhs);
  for (L1Method method : {L1Method::lp_primal, L1Method::lp_dual}) {
    LadSolver solver(design, options_for(method));
    double objective = 0;
    solver.solve(rhs, &objective);
    EXPECT_NEAR(objective, optimum, 1e-9 * optimum) << to_string(method);
  }
}

TEST(L1Regression, BatchedSolveMatchesSingleSolvesOnAnyThreadCount) {
  std::mt19937_64 random(8);
  const Eigen::MatrixXd design = gaussian(80, 3, random);
  const Eigen::MatrixXd rhs = gaussian(80, 40, random);
  for (L1Method method : kAllMethods) {
    const L1Options options = options_for(method);
    double single_sum = 0;
    Eigen::MatrixXd single(3, rhs.cols());
    LadSolver solver(design, options);
    for (Eigen::Index k = 0; k < rhs.cols(); ++k) {
      double objective = 0;
      single.col(k) = solver.solve(rhs.col(k), &objective);
      single_sum += objective;
    }
    for (unsigned threads : {1u, 2u, 3u}) {
      double batched_sum = 0;
      const Eigen::MatrixXd batched =
          solve_lad_columns(design, rhs, options, threads, &batched_sum);
      EXPECT_NEAR(batched_sum, single_sum, 1e-6 * single_sum) << to_string(method);
      EXPECT_EQ(batched.rows(), 3);
      EXPECT_EQ(batched.cols(), rhs.cols());
    }
  }
}

TEST(L1Regression, HuberApproachesL1OptimumAsGammaShrinks) {
  std::mt19937_64 random(9);
  const Eigen::MatrixXd design = gaussian(150, 4, random);
  const Eigen::VectorXd rhs = 3.0 * planted_rhs(design, gaussian(4, 1, random), 0.2, random);
  double optimum = 0;
  LadSolver(design, options_for(L1Method::lp_dual)).solve(rhs, &optimum);
  const double scale = rhs.cwiseAbs().maxCoeff();
  double previous_gap = INFINITY;
  for (double gamma : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6}) {
    L1Options options = options_for(L1Method::huber);
    options.huber_gamma = gamma;
    double objective = 0;
    const Eigen::VectorXd x = LadSolver(design, options).solve(rhs, &objective);
    const double gap = objective - optimum;
    EXPECT_GE(gap, -1e-9 * optimum) << "gamma " << gamma;
    // Bound from rho(r)/gamma being within gamma/2 of |r|: ||r||_1 - optimum <= m gamma / 2.
    EXPECT_LE(gap, 150 * gamma * scale / 2) << "gamma " << gamma;
    EXPECT_LE(gap, previous_gap + 1e-9 * optimum) << "gamma " << gamma;
    previous_gap = gap;
    // Exactness: the Huber gradient A^T clamp(r, -gamma, gamma) vanishes at the minimiser.
    const double absolute_gamma = gamma * scale;
    const Eigen::VectorXd influence = (rhs - design * x).unaryExpr([&](double r) {
      return std::clamp(r, -absolute_gamma, absolute_gamma);
    });
    EXPECT_LT((design.transpose() * influence).norm(), 1e-9 * absolute_gamma * 150) << gamma;
  }
  EXPECT_LT(previous_gap, 1e-5 * optimum);
}

TEST(L1Regression, IrlsIsCloseToTheExactOptimum) {
  std::mt19937_64 random(10);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::MatrixXd design = gaussian(100, 4, random);
    const Eigen::VectorXd rhs =
        planted_rhs(design, gaussian(4, 1, random), 0.1, random) + 0.01 * gaussian(100, 1, random);
    double optimum = 0, objective = 0;
    LadSolver(design, options_for(L1Method::lp_dual)).solve(rhs, &optimum);
    LadSolver(design, options_for(L1Method::irls)).solve(rhs, &objective);
    EXPECT_GE(objective, optimum * (1 - 1e-9));
    EXPECT_LE(objective, optimum * (1 + 1e-3)) << "trial " << trial;
  }
}

TEST(L1Regression, NonnegativeResidualInBothLpForms) {
  std::mt19937_64 random(12);
  const Eigen::MatrixXd design = gaussian(60, 3, random).cwiseAbs();
  const Eigen::VectorXd rhs = gaussian(60, 1, random).cwiseAbs() * 2;
  double free_objective = 0;
  LadSolver(design, options_for(L1Method::lp_dual)).solve(rhs, &free_objective);
  double objectives[2];
  int k = 0;
  for (L1Method method : {L1Method::lp_primal, L1Method::lp_dual}) {
    L1Options options = options_for(method);
    options.nonnegative_residual = true;
    LadSolver solver(design, options);
    const Eigen::VectorXd x = solver.solve(rhs, &objectives[k]);
    EXPECT_GE((rhs - design * x).minCoeff(), -1e-9) << to_string(method);
    EXPECT_GE(objectives[k], free_objective * (1 - 1e-9));
    // Infeasible: an observation with a zero design row and a negative right-hand side.
    Eigen::MatrixXd zero_row_design = design;
    zero_row_design.row(0).setZero();
    Eigen::VectorXd negative = rhs;
    negative[0] = -1;
    LadSolver infeasible(zero_row_design, options);
    EXPECT_THROW(infeasible.solve(negative), Error) << to_string(method);
    ++k;
  }
  EXPECT_NEAR(objectives[0], objectives[1], 1e-6 * objectives[0]);
  L1Options huber = options_for(L1Method::huber);
  huber.nonnegative_residual = true;
  EXPECT_THROW(LadSolver(design, huber), Error);
}

TEST(L1Regression, DegenerateInputsGiveFiniteDocumentedResults) {
  std::mt19937_64 random(13);
  const Eigen::MatrixXd design = gaussian(30, 3, random);
  const Eigen::VectorXd rhs = gaussian(30, 1, random);
  for (L1Method method : kAllMethods) {
    const L1Options options = options_for(method);
    SCOPED_TRACE(to_string(method));
    double objective = -1;
    // All-zero right-hand side: x = 0.
    EXPECT_EQ(LadSolver(design, options).solve(Eigen::VectorXd::Zero(30), &objective),
              Eigen::VectorXd::Zero(3));
    EXPECT_EQ(objective, 0);
    // At least as many unknowns as observations: an exact fit.
    const Eigen::MatrixXd wide = gaussian(4, 6, random);
    const Eigen::VectorXd wide_rhs = gaussian(4, 1, random);
    const Eigen::VectorXd wide_x = LadSolver(wide, options).solve(wide_rhs, &objective);
    EXPECT_TRUE(wide_x.allFinite());
    EXPECT_LT(objective, 1e-8);
    // Rank-deficient design (a repeated and a zero column): same optimum as the full-rank part.
    Eigen::MatrixXd deficient(30, 5);
    deficient << design, design.col(0), Eigen::VectorXd::Zero(30);
    double full_objective = 0;
    LadSolver(design, options).solve(rhs, &full_objective);
    const Eigen::VectorXd deficient_x = LadSolver(deficient, options).solve(rhs, &objective);
    EXPECT_TRUE(deficient_x.allFinite());
    EXPECT_NEAR(objective, full_objective, 1e-6 * full_objective);
    // Tiny and huge scales: the solution scales with the right-hand side.
    LadSolver solver(design, options);
    const Eigen::VectorXd unit_x = solver.solve(rhs);
    for (double scale : {1e-8, 1e8}) {
      const Eigen::VectorXd scaled_x = solver.solve(scale * rhs);
      EXPECT_TRUE(scaled_x.allFinite());
      EXPECT_LT((scaled_x / scale - unit_x).norm(), 1e-6 * unit_x.norm()) << scale;
    }
    // A design scaled by 1e8 or 1e-8: the solution scales inversely.
    EXPECT_LT((LadSolver(design * 1e8, options).solve(rhs) * 1e8 - unit_x).norm(),
              1e-6 * unit_x.norm());
    EXPECT_LT((LadSolver(design * 1e-8, options).solve(rhs) * 1e-8 - unit_x).norm(),
              1e-6 * unit_x.norm());
    // No observations or no unknowns.
    EXPECT_EQ(LadSolver(Eigen::MatrixXd(0, 3), options).solve(Eigen::VectorXd(0)).size(), 3);
    EXPECT_EQ(LadSolver(Eigen::MatrixXd(30, 0), options).solve(rhs, &objective).size(), 0);
    EXPECT_NEAR(objective, rhs.lpNorm<1>(), 1e-12);
  }
}

TEST(L1Regression, RefusesBadInputWithAMessage) {
  Eigen::MatrixXd design = Eigen::MatrixXd::Ones(4, 2);
  design(2, 1) = NAN;
  try {
    LadSolver solver(design, {});
    FAIL() << "NaN design accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("(2, 1)"), std::string::npos) << e.what();
  }
  LadSolver solver(Eigen::MatrixXd::Ones(4, 2), {});
  EXPECT_THROW(solver.solve(Eigen::VectorXd::Ones(3)), Error);
  Eigen::VectorXd infinite = Eigen::VectorXd::Ones(4);
  infinite[3] = INFINITY;
  EXPECT_THROW(solver.solve(infinite), Error);
  L1Options huber = options_for(L1Method::huber);
  huber.huber_gamma = 0;
  EXPECT_THROW(LadSolver(Eigen::MatrixXd::Ones(4, 2), huber), Error);
  EXPECT_THROW(solve_lad_columns(Eigen::MatrixXd::Ones(4, 2), Eigen::MatrixXd::Ones(5, 2), {}, 1),
               Error);
}

}  // namespace
}  // namespace relume
