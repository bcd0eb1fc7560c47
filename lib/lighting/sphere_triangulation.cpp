// The convex hull of directions on the unit sphere by incremental insertion (each new point
// replaces the faces it sees by a fan to their horizon), then each face sorted into a triangle or
// a gap. O(n x faces): a few milliseconds for a thousand lights.
#include "lighting/sphere_triangulation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <relume/error.hpp>
#include <string>
#include <unordered_map>

namespace relume {
namespace {

// A point this far in front of a face's plane sees it. Points here are unit vectors; the gap
// between a point of a distinct direction and the hull of the others is of the order of the
// squared spacing, far above this.
constexpr double visible_height = 1e-12;

struct HullFace {
  std::array<int, 3> corners;
  Eigen::Vector3d normal;  // unit, outwards
  double offset = 0;       // normal . corner: the plane's signed distance from the centre
  bool alive = true;
};

class Hull {
 public:
  explicit Hull(const std::vector<Eigen::Vector3d>& points) : points_(points) {}

  void add_face(int a, int b, int c) {
    HullFace face;
    face.corners = {a, b, c};
    face.normal = (points_[b] - points_[a]).cross(points_[c] - points_[a]).normalized();
    face.offset = face.normal.dot(points_[a]);
    const int index = static_cast<int>(faces_.size());
    faces_.push_back(face);
    for (int e = 0; e < 3; ++e) edge_face_[key(face.corners[e], face.corners[(e + 1) % 3])] = index;
  }

  // Inserts point p: every face it sees goes, and each horizon edge u -> v (the edge of a seen
  // face whose other face is not seen) gets the new face (u, v, p).
  void insert(int p) {
    std::vector<int> seen;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f)
      if (faces_[f].alive && height(faces_[f], p) > visible_height) seen.push_back(f);
    if (seen.empty())
      throw Error("light direction " + std::to_string(p + 1) +
                  " lies on the hull of the others (numerically): it cannot be triangulated");
    for (int f : seen) faces_[f].alive = false;
    std::vector<std::array<int, 2>> horizon;
    for (int f : seen) {
      const auto& c = faces_[f].corners;
      for (int e = 0; e < 3; ++e) {
        const int u = c[e], v = c[(e + 1) % 3];
        if (faces_[edge_face_.at(key(v, u))].alive) horizon.push_back({u, v});
      }
    }
    for (int f : seen) {
      const auto& c = faces_[f].corners;
      for (int e = 0; e < 3; ++e) edge_face_.erase(key(c[e], c[(e + 1) % 3]));
    }
    for (const auto& [u, v] : horizon) add_face(u, v, p);
  }

  double height(const HullFace& face, int p) const {
    return face.normal.dot(points_[p]) - face.offset;
  }
  const std::vector<HullFace>& faces() const { return faces_; }
  int face_of_edge(int a, int b) const { return edge_face_.at(key(a, b)); }

 private:
  std::uint64_t key(int a, int b) const {
    return std::uint64_t(a) * points_.size() + std::uint64_t(b);
  }

  const std::vector<Eigen::Vector3d>& points_;
  std::vector<HullFace> faces_;
  std::unordered_map<std::uint64_t, int> edge_face_;  // directed edge -> its face
};

// The index maximising `score` over the points.
template <class Score>
int best_point(const std::vector<Eigen::Vector3d>& points, Score score) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(points.size()); ++i)
    if (score(points[i]) > score(points[best])) best = i;
  return best;
}

}  // namespace

SphereTriangulation triangulate_sphere(const std::vector<Eigen::Vector3d>& points,
                                       double coverage_radius) {
  if (points.size() < 3)
    throw Error("moving a light needs at least three distinct light directions, got " +
                std::to_string(points.size()));
  // A first tetrahedron from far-apart points: 0, the farthest from it, the farthest from their
  // line, the farthest from their plane.
  const int a = 0;
  const int b = best_point(points, [&](const auto& p) { return (p - points[a]).norm(); });
  const Eigen::Vector3d ab = points[b] - points[a];
  const int c = best_point(points, [&](const auto& p) { return ab.cross(p - points[a]).norm(); });
  const Eigen::Vector3d normal = ab.cross(points[c] - points[a]).normalized();
  const int d =
      best_point(points, [&](const auto& p) { return std::abs(normal.dot(p - points[a])); });
  const double thickness = normal.dot(points[d] - points[a]);
  // Float directions (as files and fields hold them) put a coplanar set up to ~1e-7 off its
  // plane; a real light set is thicker by orders of magnitude (a 10-degree cap: 0.015).
  if (!(std::abs(thickness) > 1e-6))
    throw Error("the " + std::to_string(points.size()) +
                " light directions lie in one plane: moving a light needs lights that span a "
                "solid region of directions");

  Hull hull(points);
  if (thickness < 0) {  // d behind the plane of (a, b, c): keep every face turned outwards
    hull.add_face(a, b, c), hull.add_face(a, d, b), hull.add_face(b, d, c), hull.add_face(c, d, a);
  } else {
    hull.add_face(a, c, b), hull.add_face(a, b, d), hull.add_face(b, c, d), hull.add_face(c, a, d);
  }
  for (int p = 0; p < static_cast<int>(points.size()); ++p)
    if (p != a && p != b && p != c && p != d) hull.insert(p);

  // The plane of a face cuts the sphere in the face's circumcircle, of angular radius
  // acos(offset).
  const double widest_circle = 2.0 * coverage_radius;
  const auto is_gap = [&](const HullFace& face) {
    return !(face.offset > 1e-9) || std::acos(std::min(face.offset, 1.0)) > widest_circle;
  };
  SphereTriangulation triangulation;
  const auto& faces = hull.faces();
  for (const HullFace& face : faces) {
    if (!face.alive || is_gap(face)) continue;
    triangulation.triangles.push_back(face.corners);
    for (int e = 0; e < 3; ++e) {
      const int u = face.corners[e], v = face.corners[(e + 1) % 3];
      if (is_gap(faces[hull.face_of_edge(v, u)])) triangulation.rim.push_back({u, v});
    }
  }
  return triangulation;
}

}  // namespace relume
