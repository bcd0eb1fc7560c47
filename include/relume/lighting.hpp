// relume/lighting.hpp: environment maps, the light vectors they give a light set, and a built-in
// sky.
//
// Frame (shared with the light directions, DiLiGenT convention): x right, y up, z towards the
// camera; the viewer looks along -z. A direction points from the object towards where the light
// comes from. Maps come as lat-long (2:1), angular / mirror-ball light probes (1:1) or HDR Shop
// vertical crosses (3:4); the geometry of each is described in lib/lighting/environment_map.hpp.
//
// The light vector I of a map for a set of light directions: each light receives the radiance x
// solid angle of its Voronoi cell on the sphere (the map directions nearer to it, by dot product,
// than to any other light), integrated over the map's pixels.
//
// Coverage rule. A light set may cover only part of the sphere (DiLiGenT's 96 lights sit in front
// of the object). The coverage radius rho of a set is the median, over its lights, of the angle to
// the nearest other light (its typical spacing; pi for a single light). A map direction is covered
// when the nearest light is within rho; the energy of uncovered directions goes to no light and is
// reported as energy_outside. A set that covers the sphere with even spacing leaves no gaps wider
// than rho, so nothing is outside; a dense front-hemisphere set leaves about half outside.
//
// Energy is the mean of R, G and B integrated over solid angle (radiance units x steradians).
//
// Rotation. rotate_degrees turns the environment about +y counter-clockwise seen from above
// (right-hand rule): radiance that came from direction d comes from R_y(angle) d afterwards,
// with R_y(angle) (x, y, z) = (x cos + z sin, y, -x sin + z cos); +90 degrees moves +x to -z.
// It is applied by turning the light directions by -angle instead of resampling the map.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <relume/field.hpp>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

enum class EnvironmentLayout { latlong, angular, cross };

// "latlong", "angular" or "cross".
std::string layout_name(EnvironmentLayout layout);

// The geometry of a map: its layout and size in pixels.
struct MapGeometry {
  EnvironmentLayout layout = EnvironmentLayout::latlong;
  int width = 0;
  int height = 0;
};

struct EnvironmentMap {
  std::string name;  // the file it came from, for messages
  EnvironmentLayout layout = EnvironmentLayout::latlong;
  Image radiance;  // linear RGB (3 channels), every value finite

  MapGeometry geometry() const { return {layout, radiance.width, radiance.height}; }
};

// Reads a map with read_image. `layout` nullopt detects it from the aspect ratio. One channel is
// taken as grey, from three channels up the first three are R G B (alpha is ignored). Throws
// Error for unreadable files, unknown or ambiguous sizes, and NaN/Inf values (naming the pixel).
EnvironmentMap load_environment_map(const std::filesystem::path& path,
                                    std::optional<EnvironmentLayout> layout = std::nullopt);

// Wraps an image already in memory (tests, generated maps) with the same checks as loading.
EnvironmentMap make_environment_map(Image radiance, EnvironmentLayout layout, std::string name);

struct LightVector {
  LightRgb rgb;                // one row per light, R G B
  double energy_total = 0;     // over the whole map
  double energy_outside = 0;   // over directions no light covers (not in rgb)
  double coverage_radius = 0;  // rho, radians

  double outside_fraction() const { return energy_total > 0 ? energy_outside / energy_total : 0; }
};

// R_y(degrees), the rotation about the up axis described above.
Eigen::Matrix3d rotation_about_up(double degrees);

// rho of a light set (see above), radians. Throws Error for an empty set.
double coverage_radius(const LightDirections& directions);

// One map and one light set under many rotations (animated sequences): each map pixel's direction
// and radiance x solid angle are computed once, at construction, and every integrate() call only
// finds each pixel's nearest light. Throws Error for an empty light set or a zero or non-finite
// direction (construction) and a non-finite angle (integrate). threads: 0 = all cores.
class LightVectorIntegrator {
 public:
  LightVectorIntegrator(const EnvironmentMap& map, const LightDirections& directions,
                        unsigned threads = 0);
  LightVector integrate(double rotate_degrees) const;

 private:
  struct Sample {
    Eigen::Vector3d direction;     // unit, unrotated map frame
    Eigen::Vector3f weighted_rgb;  // radiance x solid angle
  };
  std::vector<Eigen::Vector3d> lights_;  // unit
  std::vector<Sample> samples_;          // the pixels that are part of the map, row by row
  double coverage_radius_ = 0;
  double energy_total_ = 0;
  unsigned threads_ = 0;
};

// LightVectorIntegrator(map, directions, threads).integrate(rotate_degrees).
LightVector integrate_light_vector(const EnvironmentMap& map, const LightDirections& directions,
                                   double rotate_degrees, unsigned threads = 0);

// One line for users: the share of the map's energy outside the light set, the total energy and
// the coverage radius.
std::string describe_coverage(const LightVector& vector);

// A built-in HDR environment: a lat-long sky with a small bright sun, a blue gradient that
// brightens towards the horizon, and a darker warm ground. It lets the demo and tests relight
// without any external map; the sun gives the high dynamic range real probes have.
struct SkyOptions {
  int width = 512;                // lat-long, height = width / 2
  double sun_elevation_deg = 35;  // above the horizon
  double sun_azimuth_deg = 30;    // about +y, from -z (straight ahead) towards +x
  double sun_radiance = 5000;     // inside the sun's disc
  double sun_radius_deg = 2.0;
};
Image render_sky(const SkyOptions& options);

}  // namespace relume
