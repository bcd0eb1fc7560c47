// Synthetic OLAT sets with exact ground truth, the input `relume synth` writes and tests and
// benchmarks render in memory: seeded coloured spheres (diffuse, glossy, near-mirror) resting on a
// checkered ground disc, seen by an orthographic camera looking along -z, lit one at a time by
// distant lights from near-uniform directions on the sphere or the front hemisphere.
//
// Frame (as in DiLiGenT): x right, y up, z towards the camera; a light direction points from the
// scene towards the light. Each light delivers irradiance 1 on a surface facing it, so the OLAT
// value of a surface point is BRDF(l, v) * max(0, n.l) * visibility, with v = (0, 0, 1):
// a Lambertian point of albedo a gives a * max(0, n.l) / pi.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <relume/field.hpp>
#include <vector>

#include "synth/synthetic_materials.hpp"

namespace relume {

class ProgressReporter;

enum class LightLayout {
  sphere,      // the whole sphere of directions (a Light Stage)
  hemisphere,  // directions with z >= 0, towards the camera (a photometric-stereo dome)
};

// `count` unit directions spread near-uniformly over the layout by a Fibonacci spiral (equal-area
// bands in z, golden-angle steps in azimuth). Deterministic; count must be >= 1.
LightDirections near_uniform_directions(int count, LightLayout layout);

struct SynthOptions {
  int width = 640;
  int height = 640;
  int lights = 253;  // the paper's Light Stage count
  LightLayout layout = LightLayout::sphere;
  std::uint64_t seed = 1;    // sphere positions, sizes, colours and materials
  int samples_per_axis = 2;  // supersampling: samples_per_axis^2 camera rays per pixel
  unsigned threads = 0;      // 0 = all cores
};

// Sane maxima of the options: beyond them a render would run for days or not fit any memory.
inline constexpr int max_synth_side = 16384;
inline constexpr int max_synth_lights = 65536;
inline constexpr int max_synth_samples_per_axis = 64;

// Throws relume::Error naming the option when a size, light count or sample count is < 1 or
// above its maximum.
void validate_synth_options(const SynthOptions& options);

struct SyntheticSphere {
  Eigen::Vector3d center;
  double radius = 0;
  SurfaceMaterial material;
};

// Orthographic view: continuous pixel coordinates (px, py), pixel centres at +0.5, map to the
// view-plane point (left + px * pixel_size, top - py * pixel_size); rays run along -z.
struct OrthographicCamera {
  double left = 0;
  double top = 0;
  double pixel_size = 0;

  Eigen::Vector2d plane_point(double px, double py) const {
    return {left + px * pixel_size, top - py * pixel_size};
  }
};

struct SyntheticScene {
  Eigen::Vector3d up;        // ground normal (the camera looks down on the ground at an angle)
  Eigen::Vector3d forward;   // along the ground, away from the camera; (1, 0, 0) is the other axis
  double ground_radius = 0;  // the ground is a disc of this radius around the origin
  double checker_size = 0;   // edge of the ground's checker squares
  std::array<Eigen::Vector3d, 2> ground_albedo;  // the two checker colours (Lambertian)
  std::vector<SyntheticSphere> spheres;          // resting on the ground, disjoint in the image
  OrthographicCamera camera;

  // Albedo of the ground's checkerboard at a point on the ground plane.
  const Eigen::Vector3d& ground_albedo_at(const Eigen::Vector3d& point) const;
};

// The scene for a seed and image size: always at least one sphere of each SurfaceKind.
SyntheticScene make_synthetic_scene(const SynthOptions& options);

// Renders the scene's OLAT set a strip of pixel rows at a time (for fields larger than memory):
// width x rows x 3 channels, one column per light of near_uniform_directions(options.lights,
// options.layout), intensities all one, mask 1 where a camera ray of any sample hits a sphere or
// the ground (0 and all-zero values elsewhere).
class SyntheticRenderer {
 public:
  // Throws Error as validate_synth_options does. Traces the camera rays of every pixel once, for
  // the mask.
  explicit SyntheticRenderer(const SynthOptions& options);

  // The whole field without values: size, lights, names, the mask.
  const ReflectanceField& header() const { return header_; }

  // Pixel rows [first_row, first_row + rows), rendered in parallel; `progress`, if given,
  // advances once per row.
  ReflectanceField render_rows(int first_row, int rows, ProgressReporter* progress = nullptr) const;

 private:
  SynthOptions options_;
  SyntheticScene scene_;
  ReflectanceField header_;
};

// The whole OLAT set at once (SyntheticRenderer over every row); throws Error also when it would
// not fit the memory budget (core/memory_budget.hpp).
ReflectanceField render_synthetic_field(const SynthOptions& options,
                                        ProgressReporter* progress = nullptr);

}  // namespace relume
