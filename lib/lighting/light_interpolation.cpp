// Spherical barycentric interpolation over a light set's triangulation, the rim fallback for
// directions outside it, and disc lights as means over the disc.
#include "lighting/light_interpolation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <relume/error.hpp>
#include <relume/lighting.hpp>
#include <string>

#include "core/text_numbers.hpp"

namespace relume {
namespace {

// Directions closer than this (radians) are the same light position.
constexpr double same_direction = 1e-9;
// A direction this far outside a triangle's edge plane still counts as inside (rounding).
constexpr double edge_tolerance = 1e-12;
// Point lights averaged over a disc light.
constexpr int disc_samples = 64;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Where the squared norm overflows or underflows, scaled before it is squared (Eigen's stable
// norm): (1, 1e308, 1) once became a zero direction, and (1e-320, 0, 0) "zero".
Eigen::Vector3d unit_direction(const Eigen::Vector3d& direction, const std::string& what) {
  if (!direction.allFinite() || !(direction.stableNorm() > 0))
    throw Error(what + " (" + number_text(direction.x()) + ", " + number_text(direction.y()) +
                ", " + number_text(direction.z()) + ") is zero or not finite");
  const double norm = direction.norm();
  return std::isnormal(norm) ? Eigen::Vector3d(direction / norm) : direction.stableNormalized();
}

}  // namespace

LightInterpolation::LightInterpolation(const LightDirections& directions)
    : lights_(static_cast<int>(directions.rows())) {
  for (int i = 0; i < lights_; ++i) {
    const Eigen::Vector3d d = unit_direction(directions.row(i).transpose().cast<double>(),
                                             "light " + std::to_string(i + 1) + "'s direction");
    const auto same = std::find_if(distinct_.begin(), distinct_.end(), [&](const auto& other) {
      return angle_between(d, other) < same_direction;
    });
    if (same != distinct_.end()) {
      lights_of_[same - distinct_.begin()].push_back(i);
      continue;
    }
    distinct_.push_back(d);
    lights_of_.push_back({i});
  }
  LightDirections distinct(distinct_.size(), 3);
  for (std::size_t j = 0; j < distinct_.size(); ++j)
    distinct.row(j) = distinct_[j].transpose().cast<float>();
  triangulation_ = triangulate_sphere(distinct_, coverage_radius(distinct));
  for (const auto& t : triangulation_.triangles) {
    TriangleCone cone;
    for (int e = 0; e < 3; ++e)
      cone.edge_normal[e] = distinct_[t[e]].cross(distinct_[t[(e + 1) % 3]]);
    cones_.push_back(cone);
  }
}

int LightInterpolation::containing_triangle(const Eigen::Vector3d& d) const {
  for (std::size_t t = 0; t < cones_.size(); ++t) {
    const auto& n = cones_[t].edge_normal;
    if (n[0].dot(d) >= -edge_tolerance && n[1].dot(d) >= -edge_tolerance &&
        n[2].dot(d) >= -edge_tolerance)
      return static_cast<int>(t);
  }
  return -1;
}

bool LightInterpolation::covers(const Eigen::Vector3d& direction) const {
  return containing_triangle(unit_direction(direction, "light direction")) >= 0;
}

void LightInterpolation::add_point_weights(const Eigen::Vector3d& d, double scale,
                                           Eigen::VectorXd& distinct) const {
  const int t = containing_triangle(d);
  if (t < 0) {
    add_rim_weights(d, scale, distinct);
    return;
  }
  // d = sum_e c_e corner_e: c_e is d's dot product with the normal of the opposite edge plane,
  // over that of corner_e (Cramer's rule), non-negative inside the triangle.
  const auto& corners = triangulation_.triangles[t];
  const auto& n = cones_[t].edge_normal;
  double coefficient[3], sum = 0;
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& opposite = n[(e + 1) % 3];
    coefficient[e] = std::max(0.0, opposite.dot(d) / opposite.dot(distinct_[corners[e]]));
    sum += coefficient[e];
  }
  for (int e = 0; e < 3; ++e) distinct[corners[e]] += scale * coefficient[e] / sum;
}

void LightInterpolation::add_rim_weights(const Eigen::Vector3d& d, double scale,
                                         Eigen::VectorXd& distinct) const {
  // The nearest point of the rim: on an edge's arc (weights on its two ends in the ratio of the
  // point's coefficients), or one of the ends.
  double nearest = std::numbers::pi * 2;
  int first = -1, second = -1;
  double first_share = 1;
  for (const auto& [a, b] : triangulation_.rim) {
    const Eigen::Vector3d& pa = distinct_[a];
    const Eigen::Vector3d& pb = distinct_[b];
    const Eigen::Vector3d normal = pa.cross(pb).normalized();
    const Eigen::Vector3d in_plane = d - d.dot(normal) * normal;
    if (in_plane.norm() > 1e-12) {
      const Eigen::Vector3d p = in_plane.normalized();
      const double alpha = p.cross(pb).dot(normal), beta = pa.cross(p).dot(normal);
      if (alpha >= 0 && beta >= 0 && angle_between(d, p) < nearest) {
        nearest = angle_between(d, p);
        first = a, second = b, first_share = alpha / (alpha + beta);
      }
    }
    for (int end : {a, b})
      if (angle_between(d, distinct_[end]) < nearest) {
        nearest = angle_between(d, distinct_[end]);
        first = end, second = -1, first_share = 1;
      }
  }
  if (first < 0)
    throw Error("light direction (" + std::to_string(d.x()) + ", " + std::to_string(d.y()) + ", " +
                std::to_string(d.z()) + ") lies in no triangle of the light set");
  distinct[first] += scale * first_share;
  if (second >= 0) distinct[second] += scale * (1 - first_share);
}

Eigen::VectorXd LightInterpolation::weights(const Eigen::Vector3d& direction,
                                            double spread_degrees) const {
  const Eigen::Vector3d d = unit_direction(direction, "light direction");
  if (!(spread_degrees >= 0 && spread_degrees <= 90))
    throw Error("light spread must be between 0 and 90 degrees, got " +
                std::to_string(spread_degrees));
  Eigen::VectorXd distinct = Eigen::VectorXd::Zero(distinct_.size());
  if (spread_degrees == 0) {
    add_point_weights(d, 1, distinct);
  } else {
    // Equal-area rings (cos theta evenly spaced) turned by the golden angle: an even cover of
    // the disc of angular radius `spread` around d.
    const Eigen::Vector3d u = d.unitOrthogonal(), v = d.cross(u);
    const double lowest_cos = std::cos(spread_degrees * std::numbers::pi / 180);
    const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int k = 0; k < disc_samples; ++k) {
      const double cos_theta = 1 - (1 - lowest_cos) * (k + 0.5) / disc_samples;
      const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
      const double phi = k * golden_angle;
      const Eigen::Vector3d sample =
          cos_theta * d + sin_theta * (std::cos(phi) * u + std::sin(phi) * v);
      add_point_weights(sample.normalized(), 1.0 / disc_samples, distinct);
    }
  }
  Eigen::VectorXd result = Eigen::VectorXd::Zero(lights_);
  for (std::size_t j = 0; j < distinct_.size(); ++j)
    for (int light : lights_of_[j]) result[light] = distinct[j] / lights_of_[j].size();
  return result;
}

LightRgb LightInterpolation::light_vector(const DirectionalLight& light) const {
  if (!(light.rgb.array() >= 0 && light.rgb.array() <= max_light_color).all())
    throw Error("light colour (" + number_text(light.rgb.x()) + ", " + number_text(light.rgb.y()) +
                ", " + number_text(light.rgb.z()) + ") must be three non-negative numbers up to " +
                number_text(max_light_color));
  const Eigen::VectorXd w = weights(light.direction, light.spread_degrees);
  LightRgb rgb(lights_, 3);
  for (int i = 0; i < lights_; ++i) rgb.row(i) = (w[i] * light.rgb).transpose().cast<float>();
  return rgb;
}

}  // namespace relume
