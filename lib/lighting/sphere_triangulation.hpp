// The spherical Delaunay triangulation of a set of unit directions (a light set), as the faces of
// their convex hull, for interpolating between captured lights (lighting/light_interpolation.hpp).
//
// Every hull face is a triangle of three directions whose circumcircle on the sphere holds no
// other direction. A light set that covers only part of the sphere (DiLiGenT's front hemisphere)
// also has hull faces that span the part no light covers: faces whose plane passes through or
// behind the centre, and faces whose empty circumcircle is wider than twice the set's typical
// spacing (the coverage radius rho of relume/lighting.hpp). Those are gaps, not triangles; the
// edges between a triangle and a gap form the rim of the covered region.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace relume {

struct SphereTriangulation {
  // Indices into the directions the triangulation was built from, counter-clockwise seen from
  // outside the sphere.
  std::vector<std::array<int, 3>> triangles;
  // Edges with a triangle on one side and a gap on the other (a -> b as in that triangle).
  std::vector<std::array<int, 2>> rim;
};

// `directions` are unit vectors with no two the same (within 1e-9 radians). Throws Error for
// fewer than three directions or when they all lie in one plane (no hull to triangulate).
SphereTriangulation triangulate_sphere(const std::vector<Eigen::Vector3d>& directions,
                                       double coverage_radius);

}  // namespace relume
