// Light layouts and the seeded layout of the synthetic scenes (spheres, ground, camera); the
// rendering itself is in synthetic_render.cpp.
#include "synth/synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <relume/error.hpp>
#include <string>

namespace relume {
namespace {

// The camera looks down on the ground at this angle above the horizon.
constexpr double kElevationDegrees = 50;
constexpr double kGroundRadius = 1.0;
constexpr double kCheckerSize = 0.25;
// Every image shows at least the view-plane square of this half-edge around kViewCentreY; spheres
// are placed so that their image circles lie inside it, minus kViewMargin.
constexpr double kViewHalfEdge = 1.05;
constexpr double kViewCentreY = 0.12;
constexpr double kViewMargin = 0.03;
constexpr int kSphereCount = 6;
constexpr double kMinRadius = 0.13;
constexpr double kMaxRadius = 0.27;
constexpr double kImageGap = 0.03;  // least gap between two spheres' image circles
constexpr int kPlacementAttempts = 2000;

// Uniform doubles from the raw 64-bit output of mt19937_64 (whose sequence the standard fixes),
// so a seed gives the same scene with every standard library.
class SeededUniform {
 public:
  explicit SeededUniform(std::uint64_t seed) : engine_(seed) {}
  double between(double low, double high) {
    return low + (high - low) * double(engine_() >> 11) * 0x1.0p-53;
  }

 private:
  std::mt19937_64 engine_;
};

Eigen::Vector3d hsv_to_rgb(double hue, double saturation, double value) {
  const double h = hue * 6;
  const int sector = std::min(5, static_cast<int>(h));
  const double f = h - sector;
  const double p = value * (1 - saturation);
  const double q = value * (1 - saturation * f);
  const double t = value * (1 - saturation * (1 - f));
  switch (sector) {
    case 0:
      return {value, t, p};
    case 1:
      return {q, value, p};
    case 2:
      return {p, value, t};
    case 3:
      return {p, q, value};
    case 4:
      return {t, p, value};
    default:
      return {value, p, q};
  }
}

SurfaceMaterial random_material(SurfaceKind kind, SeededUniform& random) {
  SurfaceMaterial material;
  material.kind = kind;
  material.albedo =
      hsv_to_rgb(random.between(0, 1), random.between(0.45, 0.85), random.between(0.4, 0.8));
  switch (kind) {
    case SurfaceKind::diffuse:
      break;
    case SurfaceKind::glossy:
      material.specular = kGlossySpecular;
      material.shininess = kGlossyShininess;
      break;
    case SurfaceKind::near_mirror:
      material.albedo *= kNearMirrorAlbedoScale;
      material.specular = kNearMirrorSpecular;
      material.shininess = kNearMirrorShininess;
      break;
  }
  return material;
}

// Whether a sphere's image circle fits the guaranteed view square and clears the placed ones.
bool fits_in_view(const Eigen::Vector3d& centre, double radius,
                  const std::vector<SyntheticSphere>& placed) {
  const double limit = kViewHalfEdge - kViewMargin;
  if (std::abs(centre.x()) + radius > limit) return false;
  if (std::abs(centre.y() - kViewCentreY) + radius > limit) return false;
  for (const auto& other : placed) {
    const double gap = (centre.head<2>() - other.center.head<2>()).norm();
    if (gap < radius + other.radius + kImageGap) return false;
  }
  return true;
}

}  // namespace

LightDirections near_uniform_directions(int count, LightLayout layout) {
  if (count < 1) throw Error("light count must be at least 1, got " + std::to_string(count));
  const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
  LightDirections directions(count, 3);
  for (int i = 0; i < count; ++i) {
    // Equal-area bands: z runs evenly over [-1, 1] (sphere) or [0, 1] (hemisphere).
    const double z = layout == LightLayout::sphere ? 1 - (2 * i + 1) / double(count)
                                                   : 1 - (i + 0.5) / double(count);
    const double ring = std::sqrt(std::max(0.0, 1 - z * z));
    const double azimuth = golden_angle * i;
    directions.row(i) << float(ring * std::cos(azimuth)), float(ring * std::sin(azimuth)), float(z);
    directions.row(i).normalize();
  }
  return directions;
}

void validate_synth_options(const SynthOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > max_synth_side ||
      options.height > max_synth_side)
    throw Error("image size must be from 1x1 to " + std::to_string(max_synth_side) + "x" +
                std::to_string(max_synth_side) + ", got " + std::to_string(options.width) + "x" +
                std::to_string(options.height));
  if (options.lights < 1 || options.lights > max_synth_lights)
    throw Error("light count must be from 1 to " + std::to_string(max_synth_lights) + ", got " +
                std::to_string(options.lights));
  if (options.samples_per_axis < 1 || options.samples_per_axis > max_synth_samples_per_axis)
    throw Error("samples per pixel axis must be from 1 to " +
                std::to_string(max_synth_samples_per_axis) + ", got " +
                std::to_string(options.samples_per_axis));
}

const Eigen::Vector3d& SyntheticScene::ground_albedo_at(const Eigen::Vector3d& point) const {
  const auto square = [&](double coordinate) {
    return static_cast<long long>(std::floor(coordinate / checker_size));
  };
  const long long parity = square(point.x()) + square(point.dot(forward));
  return ground_albedo[static_cast<std::size_t>(parity & 1)];
}

SyntheticScene make_synthetic_scene(const SynthOptions& options) {
  validate_synth_options(options);
  SyntheticScene scene;
  const double elevation = kElevationDegrees * std::numbers::pi / 180;
  scene.up = {0, std::cos(elevation), std::sin(elevation)};
  scene.forward = {0, std::sin(elevation), -std::cos(elevation)};
  scene.ground_radius = kGroundRadius;
  scene.checker_size = kCheckerSize;
  scene.ground_albedo = {Eigen::Vector3d(0.62, 0.60, 0.55), Eigen::Vector3d(0.30, 0.32, 0.36)};

  const double pixel_size = 2 * kViewHalfEdge / std::min(options.width, options.height);
  scene.camera.pixel_size = pixel_size;
  scene.camera.left = -0.5 * options.width * pixel_size;
  scene.camera.top = kViewCentreY + 0.5 * options.height * pixel_size;

  SeededUniform random(options.seed);
  std::vector<SurfaceKind> kinds = {SurfaceKind::diffuse, SurfaceKind::glossy,
                                    SurfaceKind::near_mirror};
  while (int(kinds.size()) < kSphereCount)
    kinds.push_back(static_cast<SurfaceKind>(std::min(2, int(random.between(0, 3)))));
  for (int i = kSphereCount - 1; i > 0; --i)  // Fisher-Yates: any kind may get any size
    std::swap(kinds[i], kinds[std::min(i, int(random.between(0, i + 1)))]);
  std::vector<double> radii;
  for (int i = 0; i < kSphereCount; ++i) radii.push_back(random.between(kMinRadius, kMaxRadius));
  std::sort(radii.rbegin(), radii.rend());  // the largest first, while there is room

  for (int i = 0; i < kSphereCount; ++i) {
    SyntheticSphere sphere;
    sphere.material = random_material(kinds[i], random);
    sphere.radius = radii[i];
    // Rest the sphere on a random point of the inner ground; shrink it if it finds no room.
    bool placed = false;
    while (!placed) {
      for (int attempt = 0; attempt < kPlacementAttempts && !placed; ++attempt) {
        const double distance = kGroundRadius * 0.85 * std::sqrt(random.between(0, 1));
        const double angle = random.between(0, 2 * std::numbers::pi);
        sphere.center = distance * std::cos(angle) * Eigen::Vector3d::UnitX() +
                        distance * std::sin(angle) * scene.forward + sphere.radius * scene.up;
        placed = fits_in_view(sphere.center, sphere.radius, scene.spheres);
      }
      if (!placed) sphere.radius *= 0.85;
    }
    scene.spheres.push_back(sphere);
  }
  return scene;
}

}  // namespace relume
