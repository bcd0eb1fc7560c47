// Implementation of the diffuse / specular classification (see function_classes.hpp).
#include "eval/function_classes.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <relume/error.hpp>

#include "core/parallel.hpp"

namespace relume {

FunctionClasses classify_functions(const ReflectanceField& field,
                                   const std::vector<std::uint32_t>& stored_function,
                                   double threshold, unsigned threads) {
  if (!(threshold >= 0 && threshold <= 1))
    throw Error("the diffuse threshold must be an energy fraction in [0, 1], got " +
                std::to_string(threshold));
  const int lights = field.lights();
  if (lights < 5)
    throw Error("classifying functions as diffuse needs at least 5 lights, the field has " +
                std::to_string(lights));
  Eigen::MatrixXd design(lights, 4);
  for (int i = 0; i < lights; ++i)
    design.row(i) << 1.0, field.directions(i, 0), field.directions(i, 1), field.directions(i, 2);

  FunctionClasses classes;
  classes.threshold = threshold;
  classes.diffuse.resize(stored_function.size());
  parallel_for(stored_function.size(), threads, [&](std::size_t r, unsigned) {
    const Eigen::VectorXd x = field.values.row(stored_function[r]).transpose().cast<double>();
    const double energy = x.squaredNorm(), lit_above = lit_fraction * x.maxCoeff();
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d right = Eigen::Vector4d::Zero();
    int lit = 0;
    for (int i = 0; i < lights; ++i) {
      if (!(x[i] > lit_above)) continue;
      const Eigen::Vector4d d = design.row(i).transpose();
      normal += d * d.transpose();
      right += x[i] * d;
      ++lit;
    }
    double left = 1.0;
    if (lit >= 5 && energy > 0) {
      const Eigen::Vector4d fit = normal.ldlt().solve(right);
      const Eigen::VectorXd clamped = (design * fit).cwiseMax(0.0);
      left = std::min(1.0, (x - clamped).squaredNorm() / energy);
    }
    classes.diffuse[r] = left <= threshold;
  });
  classes.diffuse_count =
      std::size_t(std::count(classes.diffuse.begin(), classes.diffuse.end(), 1));
  return classes;
}

}  // namespace relume
