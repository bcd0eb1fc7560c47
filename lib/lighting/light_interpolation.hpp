// Moving a light between the captured ones: the light vector of a directional light from any
// direction, as smooth interpolation weights over the light set.
//
// Method: spherical barycentric weights on the Delaunay triangulation of the light directions
// (lighting/sphere_triangulation.hpp). A direction d inside the spherical triangle (a, b, c)
// gets weights proportional to the (non-negative) coefficients of d = alpha a + beta b + gamma c,
// normalised to sum to one (the planar barycentric coordinates of d's projection onto the
// triangle's plane). Chosen over radial basis functions because it has the three properties a
// relit image needs at once: at a captured direction the weight is 1 on that light alone (the
// image is the captured photograph), weights are never negative (a negative light gives negative
// pixels), and they change continuously as d moves (across an edge only the edge's two lights
// carry weight, from either side). An interpolating RBF has negative weights between lights; a
// normalised positive kernel blurs the captured images into each other.
//
// Directions that no triangle covers (behind DiLiGenT's front hemisphere) take the weights of
// the nearest point on the rim of the covered region: the light stays as close to where it was
// asked as the capture allows, and still moves continuously, except across the directions that
// have several nearest rim points (around the point opposite the cover's centre), where it
// jumps from one side of the rim to the other.
//
// A spread s > 0 makes it a disc light of angular radius s: its weights are the mean of the
// point-light weights over 64 directions spread evenly over the disc (equal solid angle each).
// Lights of the same direction (within 1e-9 radians) share its weight equally.
#pragma once

#include <Eigen/Core>
#include <relume/field.hpp>
#include <vector>

#include "lighting/sphere_triangulation.hpp"

namespace relume {

// The largest colour component of a moved light: keeps relit floats far from overflow.
inline constexpr double max_light_color = 1e6;

struct DirectionalLight {
  Eigen::Vector3d direction{0, 0, 1};  // towards the light, camera frame; need not be unit
  Eigen::Vector3d rgb{1, 1, 1};        // colour and intensity: 1 = one captured light's
  double spread_degrees = 0;           // angular radius of the disc, 0 = a point light
};

class LightInterpolation {
 public:
  // Throws Error for a zero or non-finite direction, or a set that cannot be triangulated
  // (fewer than three distinct directions, or all in one plane).
  explicit LightInterpolation(const LightDirections& directions);

  // One weight per light: non-negative, summing to one. Throws Error for a zero or non-finite
  // direction or a spread outside [0, 90] degrees.
  Eigen::VectorXd weights(const Eigen::Vector3d& direction, double spread_degrees = 0) const;

  // weights(light.direction, light.spread_degrees) times light.rgb: the light vector to relight
  // with. Throws Error for a colour component that is not a number from 0 to max_light_color, as
  // well as for what weights refuses.
  LightRgb light_vector(const DirectionalLight& light) const;

  // True when a triangle holds `direction` (any length, normalized here), false when it takes the
  // rim's weights.
  bool covers(const Eigen::Vector3d& direction) const;

  // The triangulation is over the distinct directions (unit vectors); distinct direction j is
  // the direction of lights lights_of()[j] (several when lights share a direction). With these a
  // renderer outside C++ (the published web page) computes the same weights.
  const SphereTriangulation& triangulation() const { return triangulation_; }
  const std::vector<Eigen::Vector3d>& distinct_directions() const { return distinct_; }
  const std::vector<std::vector<int>>& lights_of() const { return lights_of_; }

 private:
  // The inward normals of a triangle's three edge planes: d lies in the triangle's cone when
  // its dot product with each is >= 0.
  struct TriangleCone {
    Eigen::Vector3d edge_normal[3];
  };
  // Adds scale x the point-light weights of unit direction d to `distinct` (one per distinct
  // direction).
  void add_point_weights(const Eigen::Vector3d& d, double scale, Eigen::VectorXd& distinct) const;
  void add_rim_weights(const Eigen::Vector3d& d, double scale, Eigen::VectorXd& distinct) const;
  int containing_triangle(const Eigen::Vector3d& d) const;  // -1 when none holds d

  int lights_ = 0;
  std::vector<Eigen::Vector3d> distinct_;    // unit directions, no two the same
  std::vector<std::vector<int>> lights_of_;  // distinct direction -> its lights
  SphereTriangulation triangulation_;        // over distinct_
  std::vector<TriangleCone> cones_;          // one per triangle
};

}  // namespace relume
