// Solid-angle integration of an environment map over the Voronoi cells of a light set, with a
// coarse cube grid of candidate lights so that each map pixel tests a few lights, not all.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <relume/error.hpp>
#include <relume/lighting.hpp>
#include <vector>

#include "core/parallel.hpp"
#include "lighting/environment_map.hpp"

namespace relume {
namespace {

constexpr double pi = std::numbers::pi;

using UnitDirections = std::vector<Eigen::Vector3d>;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

UnitDirections unit_directions(const LightDirections& directions) {
  if (directions.rows() == 0) throw Error("the light set is empty");
  UnitDirections units;
  for (Eigen::Index i = 0; i < directions.rows(); ++i) {
    const Eigen::Vector3d d = directions.row(i).transpose().cast<double>();
    if (!d.allFinite() || !(d.norm() > 0))
      throw Error("light " + std::to_string(i + 1) + " has a zero or non-finite direction");
    units.push_back(d.normalized());
  }
  return units;
}

// Directions grouped by a cube grid: each cell lists the lights that can be the nearest one
// (largest dot product) to some direction in the cell while within the coverage radius rho of it.
// With c the cell's centre direction, delta its angular radius and alpha the angle from c to its
// nearest light, the nearest light to any direction in the cell lies within alpha + 2 delta of c
// (triangle inequality), and a light farther than rho + delta from c covers no direction of the
// cell. A cell farther than rho + delta from every light has no candidates: all of it is outside.
class NearestLightGrid {
 public:
  NearestLightGrid(const UnitDirections& lights, double coverage_radius) : lights_(lights) {
    const double per_face = std::sqrt(double(lights.size()) / 6.0);
    cells_per_edge_ = std::clamp(static_cast<int>(std::ceil(2.0 * per_face)), 2, 64);
    const int cells = 6 * cells_per_edge_ * cells_per_edge_;
    offsets_.push_back(0);
    for (int cell = 0; cell < cells; ++cell) {
      const int face = cell / (cells_per_edge_ * cells_per_edge_);
      const int i = cell / cells_per_edge_ % cells_per_edge_;
      const int j = cell % cells_per_edge_;
      const Eigen::Vector3d centre = face_point(face, i + 0.5, j + 0.5).normalized();
      double radius = 0;
      for (int corner = 0; corner < 4; ++corner) {
        const Eigen::Vector3d corner_direction =
            face_point(face, i + corner % 2, j + corner / 2).normalized();
        radius = std::max(radius, angle_between(centre, corner_direction));
      }
      double nearest_dot = -1.0;
      for (const auto& light : lights) nearest_dot = std::max(nearest_dot, centre.dot(light));
      const double nearest_angle = std::acos(std::min(nearest_dot, 1.0));
      // The margin only admits a few more candidates; it guards the bounds against rounding.
      const double reach = std::min(nearest_angle + 2.0 * radius, coverage_radius + radius) + 1e-7;
      const double reach_dot = reach >= pi ? -2.0 : std::cos(reach);
      for (std::size_t l = 0; l < lights.size(); ++l)
        if (centre.dot(lights[l]) >= reach_dot) candidates_.push_back(static_cast<int>(l));
      offsets_.push_back(candidates_.size());
    }
  }

  // Index of the nearest light (lowest index among equals) and its dot product with `d` (unit);
  // (-1, -2) where no light can cover `d`. Only meaningful when the dot is at least cos(rho).
  std::pair<int, double> nearest(const Eigen::Vector3d& d) const {
    const int cell = cell_of(d);
    int best = -1;
    double best_dot = -2.0;
    for (std::size_t k = offsets_[cell]; k < offsets_[cell + 1]; ++k) {
      const double dot = d.dot(lights_[candidates_[k]]);
      if (dot > best_dot) {
        best_dot = dot;
        best = candidates_[k];
      }
    }
    return {best, best_dot};
  }

 private:
  // Faces: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z; s, t in [0, cells_per_edge] across the face.
  Eigen::Vector3d face_point(int face, double s, double t) const {
    const double a = 2.0 * s / cells_per_edge_ - 1.0;
    const double b = 2.0 * t / cells_per_edge_ - 1.0;
    const double sign = face % 2 == 0 ? 1.0 : -1.0;
    switch (face / 2) {
      case 0:
        return {sign, a, b};
      case 1:
        return {a, sign, b};
      default:
        return {a, b, sign};
    }
  }

  int cell_of(const Eigen::Vector3d& d) const {
    const Eigen::Vector3d m = d.cwiseAbs();
    int axis = 0;
    if (m.y() > m[axis]) axis = 1;
    if (m.z() > m[axis]) axis = 2;
    const int face = 2 * axis + (d[axis] > 0 ? 0 : 1);
    const int first = axis == 0 ? 1 : 0;
    const int second = axis == 2 ? 1 : 2;
    const auto index = [&](double coordinate) {
      const double s = (coordinate / m[axis] + 1.0) / 2.0 * cells_per_edge_;
      return std::clamp(static_cast<int>(std::floor(s)), 0, cells_per_edge_ - 1);
    };
    return (face * cells_per_edge_ + index(d[first])) * cells_per_edge_ + index(d[second]);
  }

  const UnitDirections& lights_;
  int cells_per_edge_ = 2;
  std::vector<std::size_t> offsets_;
  std::vector<int> candidates_;
};

double median_nearest_neighbour_angle(const UnitDirections& lights) {
  std::vector<double> nearest;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    double best = pi;
    bool found = false;
    for (std::size_t j = 0; j < lights.size(); ++j) {
      if (i == j) continue;
      const double angle = angle_between(lights[i], lights[j]);
      if (angle < 1e-9) continue;  // a repeated direction is not a neighbour
      best = std::min(best, angle);
      found = true;
    }
    if (found) nearest.push_back(best);
  }
  if (nearest.empty()) return pi;
  const auto middle = nearest.begin() + nearest.size() / 2;
  std::nth_element(nearest.begin(), middle, nearest.end());
  if (nearest.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(nearest.begin(), middle));
}

double mean_of(const Eigen::Vector3f& rgb) { return (double(rgb[0]) + rgb[1] + rgb[2]) / 3.0; }

}  // namespace

Eigen::Matrix3d rotation_about_up(double degrees) {
  const double angle = degrees * pi / 180.0;
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d r;
  r << c, 0, s, 0, 1, 0, -s, 0, c;
  return r;
}

double coverage_radius(const LightDirections& directions) {
  return median_nearest_neighbour_angle(unit_directions(directions));
}

LightVectorIntegrator::LightVectorIntegrator(const EnvironmentMap& map,
                                             const LightDirections& directions, unsigned threads)
    : lights_(unit_directions(directions)), threads_(threads) {
  coverage_radius_ = median_nearest_neighbour_angle(lights_);
  const MapGeometry geometry = map.geometry();
  const int chunk_count = std::min(64, geometry.height);
  std::vector<std::vector<Sample>> chunks(chunk_count);
  parallel_for(chunk_count, threads, [&](std::size_t chunk, unsigned) {
    const int row_begin = static_cast<int>(chunk * geometry.height / chunk_count);
    const int row_end = static_cast<int>((chunk + 1) * geometry.height / chunk_count);
    for (int y = row_begin; y < row_end; ++y)
      for (int x = 0; x < geometry.width; ++x) {
        const double solid_angle = pixel_solid_angle(geometry, x, y);
        if (solid_angle <= 0) continue;
        Sample sample;
        sample.direction = *pixel_direction(geometry, x, y);
        for (int c = 0; c < 3; ++c)
          sample.weighted_rgb[c] = static_cast<float>(map.radiance.at(x, y, c) * solid_angle);
        chunks[chunk].push_back(sample);
      }
  });
  for (auto& chunk : chunks) samples_.insert(samples_.end(), chunk.begin(), chunk.end());
  for (const Sample& sample : samples_) energy_total_ += mean_of(sample.weighted_rgb);
}

LightVector LightVectorIntegrator::integrate(double rotate_degrees) const {
  if (!std::isfinite(rotate_degrees))
    throw Error("rotation angle must be finite, got " + std::to_string(rotate_degrees));
  // Rotating the map by R is the same as looking up the unrotated map with lights turned by R^-1.
  const Eigen::Matrix3d inverse = rotation_about_up(-rotate_degrees);
  UnitDirections lights = lights_;
  for (auto& light : lights) light = inverse * light;
  const NearestLightGrid grid(lights, coverage_radius_);
  const double covered_dot = std::cos(coverage_radius_);

  // Fixed ranges of samples, summed in order: the result does not depend on the thread count.
  const std::size_t range_count =
      std::min<std::size_t>(64, std::max<std::size_t>(samples_.size(), 1));
  std::vector<std::vector<double>> range_rgb(range_count);
  std::vector<double> range_outside(range_count, 0.0);
  parallel_for(range_count, threads_, [&](std::size_t range, unsigned) {
    std::vector<double>& rgb = range_rgb[range];
    rgb.assign(lights.size() * 3, 0.0);
    const std::size_t begin = range * samples_.size() / range_count;
    const std::size_t end = (range + 1) * samples_.size() / range_count;
    for (std::size_t k = begin; k < end; ++k) {
      const Sample& sample = samples_[k];
      const auto [light, dot] = grid.nearest(sample.direction);
      if (dot < covered_dot) {
        range_outside[range] += mean_of(sample.weighted_rgb);
        continue;
      }
      for (int c = 0; c < 3; ++c) rgb[3 * light + c] += sample.weighted_rgb[c];
    }
  });

  LightVector result;
  result.coverage_radius = coverage_radius_;
  result.energy_total = energy_total_;
  std::vector<double> rgb(lights.size() * 3, 0.0);
  for (std::size_t range = 0; range < range_count; ++range) {
    for (std::size_t k = 0; k < rgb.size(); ++k) rgb[k] += range_rgb[range][k];
    result.energy_outside += range_outside[range];
  }
  result.rgb.resize(static_cast<Eigen::Index>(lights.size()), 3);
  for (std::size_t l = 0; l < lights.size(); ++l)
    for (int c = 0; c < 3; ++c) result.rgb(static_cast<Eigen::Index>(l), c) = float(rgb[3 * l + c]);
  return result;
}

LightVector integrate_light_vector(const EnvironmentMap& map, const LightDirections& directions,
                                   double rotate_degrees, unsigned threads) {
  return LightVectorIntegrator(map, directions, threads).integrate(rotate_degrees);
}

std::string describe_coverage(const LightVector& vector) {
  char text[256];
  std::snprintf(text, sizeof text,
                "%.2f%% of the map's energy falls outside the light set (coverage radius %.2f "
                "degrees); total energy %.6g",
                100.0 * vector.outside_fraction(), vector.coverage_radius * 180.0 / pi,
                vector.energy_total);
  return text;
}

}  // namespace relume
