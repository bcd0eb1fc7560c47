// Implementation of the diffuse / specular classification (see function_classes.hpp).
#include "eval/function_classes.hpp"

#include <Eigen/QR>
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
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(design);
  const Eigen::MatrixXf q =
      (qr.householderQ() * Eigen::MatrixXd::Identity(lights, 4)).cast<float>();  // lights x 4

  FunctionClasses classes;
  classes.threshold = threshold;
  classes.linear_residual.resize(stored_function.size());
  classes.diffuse.resize(stored_function.size());
  parallel_for(stored_function.size(), threads, [&](std::size_t r, unsigned) {
    const auto x = field.values.row(stored_function[r]);
    const double energy = x.cast<double>().squaredNorm();
    const double explained = (x * q).cast<double>().squaredNorm();
    const double left = energy > 0 ? std::max(0.0, 1.0 - explained / energy) : 1.0;
    classes.linear_residual[r] = static_cast<float>(left);
    classes.diffuse[r] = left <= threshold;
  });
  classes.diffuse_count =
      std::size_t(std::count(classes.diffuse.begin(), classes.diffuse.end(), 1));
  return classes;
}

}  // namespace relume
