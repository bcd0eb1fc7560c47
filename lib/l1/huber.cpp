// The paper's QP alternative to the L1 LP: the Huber M-estimator
//     min_x sum_i rho(b_i - A_i x),  rho(r) = r^2/2 for |r| <= gamma, gamma |r| - gamma^2/2 beyond,
// which is the QP  min 1/2 |u|^2 + gamma (sum k + sum l)  s.t.  A x + u + k - l = b, k, l >= 0.
// GLPK has no QP solver; the objective is convex and piecewise quadratic in the few unknowns, so it
// is minimised exactly by Newton steps on the current quadratic set with an exact line search
// along the piecewise-quadratic path. Continuation: the least-squares fit is the exact minimiser
// for gamma >= its largest residual; gamma then shrinks tenfold per stage to the target, each
// stage warm-started from the last, so the quadratic set stays large enough for Newton steps.
// As gamma -> 0 the minimiser approaches an L1 minimiser: ||b - A x||_1 <= L1 optimum + m gamma/2.
#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "l1/methods.hpp"

namespace relume {
namespace {

constexpr int kMaxNewtonStepsPerStage = 100;
constexpr double kStageShrink = 0.1;

class HuberMethod final : public LadMethod {
 public:
  HuberMethod(const Eigen::MatrixXd& design, double gamma)
      : design_(design), gamma_(gamma), least_squares_(design) {
    // Relative ridge that keeps a Newton system solvable when the quadratic set is too small.
    const double scale = std::max(1.0, design_.squaredNorm() / double(design_.cols()));
    ridge_ = 1e-12 * scale;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    Eigen::VectorXd x = least_squares_.solve(rhs);
    double stage_gamma = (rhs - design_ * x).cwiseAbs().maxCoeff();
    while (stage_gamma > gamma_) {
      stage_gamma = std::max(gamma_, stage_gamma * kStageShrink);
      minimise(rhs, stage_gamma, x);
    }
    return x;
  }

 private:
  static double clamp(double r, double gamma) { return std::clamp(r, -gamma, gamma); }

  static double huber(const Eigen::VectorXd& residual, double gamma) {
    double sum = 0;
    for (double r : residual)
      sum += std::abs(r) <= gamma ? 0.5 * r * r : gamma * std::abs(r) - 0.5 * gamma * gamma;
    return sum;
  }

  // Newton steps with exact line search until the gradient vanishes or the objective stalls.
  void minimise(const Eigen::VectorXd& rhs, double gamma, Eigen::VectorXd& x) const {
    const Eigen::Index unknowns = design_.cols();
    Eigen::VectorXd residual = rhs - design_ * x;
    double objective = huber(residual, gamma);
    for (int step = 0; step < kMaxNewtonStepsPerStage; ++step) {
      const Eigen::VectorXd influence =
          residual.unaryExpr([gamma](double r) { return clamp(r, gamma); });
      const Eigen::VectorXd descent = design_.transpose() * influence;  // minus the gradient
      if (descent.lpNorm<Eigen::Infinity>() <= 1e-14 * gamma * double(rhs.size())) return;
      Eigen::MatrixXd hessian = ridge_ * Eigen::MatrixXd::Identity(unknowns, unknowns);
      for (Eigen::Index i = 0; i < residual.size(); ++i)
        if (std::abs(residual[i]) <= gamma)
          hessian.selfadjointView<Eigen::Lower>().rankUpdate(design_.row(i).transpose());
      const Eigen::VectorXd direction =
          hessian.selfadjointView<Eigen::Lower>().ldlt().solve(descent);
      const Eigen::VectorXd change = design_ * direction;  // residual moves by -alpha * change
      const double alpha = exact_step(residual, change, gamma);
      if (!(alpha > 0)) return;
      const Eigen::VectorXd next_x = x + alpha * direction;
      const Eigen::VectorXd next_residual = rhs - design_ * next_x;
      const double next_objective = huber(next_residual, gamma);
      if (!(next_objective < objective)) return;
      const bool stalled = objective - next_objective <= 1e-15 * objective;
      x = next_x;
      residual = next_residual;
      objective = next_objective;
      if (stalled) return;
    }
  }

  // The minimiser over alpha >= 0 of sum rho(r - alpha c): the root of its derivative, which is
  // continuous, non-decreasing and piecewise linear with breaks where some |r_i - alpha c_i| =
  // gamma.
  static double exact_step(const Eigen::VectorXd& residual, const Eigen::VectorXd& change,
                           double gamma) {
    double derivative = 0;                          // d/d alpha at alpha = 0
    double slope = 0;                               // sum of c_i^2 over the quadratic set
    std::vector<std::pair<double, double>> breaks;  // (alpha, slope change)
    for (Eigen::Index i = 0; i < residual.size(); ++i) {
      const double r = residual[i], c = change[i];
      derivative -= clamp(r, gamma) * c;
      if (c == 0) continue;
      const double a = (r - gamma) / c, b = (r + gamma) / c;
      const double enter = std::min(a, b), leave = std::max(a, b);
      if (leave <= 0) continue;
      if (enter <= 0) {
        slope += c * c;
      } else {
        breaks.emplace_back(enter, c * c);
      }
      breaks.emplace_back(leave, -c * c);
    }
    if (derivative >= 0) return 0;
    std::sort(breaks.begin(), breaks.end());
    double alpha = 0;
    for (const auto& [at, slope_change] : breaks) {
      if (slope > 0 && derivative + slope * (at - alpha) >= 0) return alpha - derivative / slope;
      derivative += slope * (at - alpha);
      alpha = at;
      slope = std::max(0.0, slope + slope_change);
    }
    return slope > 0 ? alpha - derivative / slope : alpha;
  }

  Eigen::MatrixXd design_;
  double gamma_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> least_squares_;
  double ridge_;
};

}  // namespace

std::unique_ptr<LadMethod> make_huber_method(const Eigen::MatrixXd& design, double gamma) {
  return std::make_unique<HuberMethod>(design, gamma);
}

}  // namespace relume
