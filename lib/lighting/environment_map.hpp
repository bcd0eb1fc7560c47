// Environment-map geometry and layout rules behind relume/lighting.hpp: layout detection, and the
// mapping between image positions and directions on the sphere with each pixel's solid angle.
//
// Frame (shared with the light directions, DiLiGenT convention): x right, y up, z towards the
// camera; the viewer looks along -z. A direction points from the object towards where the light
// comes from. Up axis = +y. The three layouts use the conventions of Debevec's light probes and
// HDR Shop (the same as soravux/skylibs, envmap/projections.py); each is "seen from inside":
// looking along a map's forward direction (-z) with +y up, +x is on the right, not mirrored.
//
// Image positions are continuous: pixel (i, j) covers [i, i+1) x [j, j+1), rows top to bottom.
//
//  - latlong (equirectangular), W x H, normally 2:1: u = x / W in [0, 1) left to right,
//    v = y / H in [0, 1) top to bottom; theta = pi v (angle from +y), phi = 2 pi (u - 1/2);
//    direction = (sin phi sin theta, cos theta, -cos phi sin theta). The image centre looks
//    along -z, u = 3/4 along +x, u = 1/4 along -x, the left/right edges along +z, the top row up.
//    Poly Haven / Blender maps have the same handedness (u grows to the right as seen from
//    inside); only their azimuth origin differs, which --rotate adjusts.
//  - angular (Debevec light probe), square: a = 2x/W - 1 (right), b = 1 - 2y/H (up),
//    r = sqrt(a^2 + b^2) <= 1, theta = pi r (angle from -z);
//    direction = (a/r sin theta, b/r sin theta, -cos theta). The centre looks along -z, the rim
//    is +z. Pixels whose centre lies outside the disc are not part of the map.
//  - cross (HDR Shop vertical cross), 3:4 with square faces of side s = W/3, in cells
//    (column, row): (1,0) +y, (0,1) -x, (1,1) -z, (2,1) +x, (1,2) -y, (1,3) +z. With face
//    coordinates a (right) and b (up) in [-1, 1], the unnormalised directions are
//    +y: (a, 1, b); -x: (-1, b, -a); -z: (a, b, -1); +x: (1, b, a); -y: (a, -1, -b);
//    +z: (a, -b, 1), i.e. the faces unfold around the front face and the back face (+z) hangs
//    below the bottom face, upside down. The six empty cells are not part of the map.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <relume/lighting.hpp>
#include <string>

namespace relume {

// Parses a --layout value: "auto" gives nullopt (detect from the size); anything other than the
// four names throws Error.
std::optional<EnvironmentLayout> parse_layout_option(const std::string& text);

// The layout of a width x height map from its aspect ratio: exactly 2:1 latlong, 1:1 angular,
// 3:4 cross. Any other size throws Error naming `name` and the size (and the nearest layout when
// the ratio is close to one but not exact).
EnvironmentLayout detect_layout(int width, int height, const std::string& name);

// Throws Error naming `name` when a map of this size cannot have this layout (angular must be
// square, cross 3:4, latlong at least 2 x 1).
void check_layout_size(EnvironmentLayout layout, int width, int height, const std::string& name);

// Unit direction at continuous image position (x, y); nullopt where the position is not part of
// the map (outside the angular disc or the cross faces).
std::optional<Eigen::Vector3d> image_to_direction(const MapGeometry& map, double x, double y);

// Direction of pixel (px, py)'s centre; nullopt for pixels that are not part of the map.
std::optional<Eigen::Vector3d> pixel_direction(const MapGeometry& map, int px, int py);

// The pixel of the map that holds `direction` (need not be normalised, must not be zero): always
// a pixel that is part of the map.
Eigen::Vector2i direction_to_pixel(const MapGeometry& map, const Eigen::Vector3d& direction);

// Solid angle in steradians covered by pixel (px, py); 0 for pixels that are not part of the map.
// Exact for latlong and cross; for angular the pixel's share of the disc is integrated
// numerically. Over a whole map they sum to 4 pi.
double pixel_solid_angle(const MapGeometry& map, int px, int py);

}  // namespace relume
