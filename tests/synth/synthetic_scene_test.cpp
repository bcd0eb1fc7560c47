// Tests for the synthetic OLAT renderer and `relume synth`: light layouts, scene layout,
// determinism, the Lambert normalisation and cast shadows checked against ray tests written here
// independently of the renderer, the near-mirror highlight, and a CLI round trip through
// load_field.
#include "synth/synthetic_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {
using Eigen::Vector3d;

SynthOptions small_options(int width, int height, int lights) {
  SynthOptions options;
  options.width = width;
  options.height = height;
  options.lights = lights;
  options.threads = 2;
  return options;
}

Vector3d light_direction(const ReflectanceField& field, int i) {
  return field.directions.row(i).transpose().cast<double>();
}

// Centre of pixel (x, y) on the view plane, from the documented orthographic mapping.
Eigen::Vector2d pixel_centre(const SyntheticScene& scene, int x, int y) {
  return {scene.camera.left + (x + 0.5) * scene.camera.pixel_size,
          scene.camera.top - (y + 0.5) * scene.camera.pixel_size};
}

// Smallest positive t where origin + t * direction meets the sphere, or -1 (quadratic formula).
double ray_sphere(const Vector3d& origin, const Vector3d& direction, const SyntheticSphere& s) {
  const Vector3d offset = origin - s.center;
  const double b = 2 * direction.dot(offset);
  const double c = offset.dot(offset) - s.radius * s.radius;
  const double discriminant = b * b - 4 * c;
  if (discriminant < 0) return -1;
  const double near = (-b - std::sqrt(discriminant)) / 2, far = (-b + std::sqrt(discriminant)) / 2;
  if (near > 1e-9) return near;
  return far > 1e-9 ? far : -1;
}

// Whether anything but sphere `own` (-1: none) blocks the way from `point` towards `light`.
bool blocked(const SyntheticScene& scene, const Vector3d& point, const Vector3d& light, int own) {
  for (int k = 0; k < int(scene.spheres.size()); ++k)
    if (k != own && ray_sphere(point, light, scene.spheres[k]) > 0) return true;
  const double height = point.dot(scene.up), rise = light.dot(scene.up);
  if (height > 1e-9 && rise < 0) {
    const Vector3d on_ground = point + (height / -rise) * light;
    if (on_ground.norm() <= scene.ground_radius) return true;
  }
  return false;
}

int sphere_of_kind(const SyntheticScene& scene, SurfaceKind kind) {
  for (int k = 0; k < int(scene.spheres.size()); ++k)
    if (scene.spheres[k].material.kind == kind) return k;
  return -1;
}

// Pixels whose centre lies within `fraction` of the sphere's image radius from its image centre.
std::vector<std::pair<int, int>> pixels_on_sphere(const SyntheticScene& scene,
                                                  const SynthOptions& o,
                                                  const SyntheticSphere& sphere, double fraction) {
  std::vector<std::pair<int, int>> pixels;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x)
      if ((pixel_centre(scene, x, y) - sphere.center.head<2>()).norm() < fraction * sphere.radius)
        pixels.emplace_back(x, y);
  return pixels;
}

double nearest_neighbour_angle(const LightDirections& d, int i) {
  double best = std::numbers::pi;
  for (int j = 0; j < d.rows(); ++j)
    if (j != i)
      best = std::min(best, std::acos(std::clamp(double(d.row(i).dot(d.row(j))), -1.0, 1.0)));
  return best;
}

TEST(NearUniformDirections, SphereIsUnitAndNearUniform) {
  for (int count : {40, 253}) {
    const LightDirections d = near_uniform_directions(count, LightLayout::sphere);
    ASSERT_EQ(d.rows(), count);
    double sum = 0, smallest = 10, below = 0;
    for (int i = 0; i < count; ++i) {
      EXPECT_NEAR(d.row(i).norm(), 1.0, 1e-6);
      const double angle = nearest_neighbour_angle(d, i);
      sum += angle;
      smallest = std::min(smallest, angle);
      below += d(i, 2) < 0;
    }
    const double mean = sum / count;
    EXPECT_GT(smallest, mean / 2) << count << " lights";
    // Equal-area spacing: the mean gap is close to that of a hexagonal grid, sqrt(8 pi / (sqrt3
    // N)).
    EXPECT_NEAR(mean, std::sqrt(8 * std::numbers::pi / (std::sqrt(3.0) * count)), 0.15 * mean);
    EXPECT_EQ(below, count / 2) << "half the sphere lies behind the scene";
    EXPECT_LT(d.colwise().sum().norm(), 0.05 * count) << "directions are balanced";
  }
}

TEST(NearUniformDirections, HemisphereFacesTheCamera) {
  for (int count : {1, 7, 96, 253}) {
    const LightDirections d = near_uniform_directions(count, LightLayout::hemisphere);
    ASSERT_EQ(d.rows(), count);
    for (int i = 0; i < count; ++i) {
      EXPECT_GE(d(i, 2), 0.0f);
      EXPECT_NEAR(d.row(i).norm(), 1.0, 1e-6);
    }
  }
  const LightDirections d = near_uniform_directions(96, LightLayout::hemisphere);
  double smallest = 10, sum = 0;
  for (int i = 0; i < 96; ++i) {
    const double angle = nearest_neighbour_angle(d, i);
    smallest = std::min(smallest, angle);
    sum += angle;
  }
  EXPECT_GT(smallest, sum / 96 / 2);
}

TEST(SyntheticScene, RefusesBadOptions) {
  EXPECT_THROW(near_uniform_directions(0, LightLayout::sphere), Error);
  SynthOptions options = small_options(8, 8, 0);
  EXPECT_THROW(render_synthetic_field(options), Error);
  options = small_options(0, 8, 4);
  EXPECT_THROW(render_synthetic_field(options), Error);
  options = small_options(8, -1, 4);
  EXPECT_THROW(render_synthetic_field(options), Error);
  options = small_options(8, 8, 4);
  options.samples_per_axis = 0;
  EXPECT_THROW(render_synthetic_field(options), Error);
  try {
    render_synthetic_field(small_options(8, 8, -3));
    ADD_FAILURE() << "a negative light count was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("got -3"), std::string::npos) << e.what();
  }
}

TEST(SyntheticScene, SpheresRestOnTheGroundAndShowEveryMaterial) {
  for (std::uint64_t seed : {1, 2, 3, 17, 12345}) {
    SynthOptions options = small_options(64, 48, 4);
    options.seed = seed;
    const SyntheticScene scene = make_synthetic_scene(options);
    for (SurfaceKind kind : {SurfaceKind::diffuse, SurfaceKind::glossy, SurfaceKind::near_mirror})
      EXPECT_GE(sphere_of_kind(scene, kind), 0) << "seed " << seed;
    for (std::size_t a = 0; a < scene.spheres.size(); ++a) {
      const SyntheticSphere& s = scene.spheres[a];
      EXPECT_NEAR(s.center.dot(scene.up), s.radius, 1e-12);
      EXPECT_LT((s.center - s.radius * scene.up).norm(), scene.ground_radius);
      for (std::size_t b = a + 1; b < scene.spheres.size(); ++b)
        EXPECT_GT((s.center.head<2>() - scene.spheres[b].center.head<2>()).norm(),
                  s.radius + scene.spheres[b].radius)
            << "image circles of spheres " << a << " and " << b << " overlap";
    }
  }
}

TEST(SyntheticScene, DeterministicForASeedAndDifferentAcrossSeeds) {
  SynthOptions options = small_options(48, 48, 40);
  const ReflectanceField first = render_synthetic_field(options);
  options.threads = 1;
  const ReflectanceField again = render_synthetic_field(options);
  EXPECT_TRUE(first.values == again.values);
  EXPECT_EQ(first.mask, again.mask);
  options.seed = 2;
  const ReflectanceField other = render_synthetic_field(options);
  EXPECT_GT((first.values - other.values).cwiseAbs().maxCoeff(), 0.1f);
}

TEST(SyntheticScene, FieldShapeValuesAndMask) {
  SynthOptions options = small_options(48, 40, 40);
  options.layout = LightLayout::hemisphere;
  const ReflectanceField field = render_synthetic_field(options);
  EXPECT_EQ(field.width, 48);
  EXPECT_EQ(field.height, 40);
  EXPECT_EQ(field.channels, 3);
  EXPECT_EQ(field.lights(), 40);
  EXPECT_EQ(field.functions(), 48 * 40 * 3);
  EXPECT_TRUE(field.intensities.isOnes());
  EXPECT_TRUE(field.directions.isApprox(near_uniform_directions(40, LightLayout::hemisphere)));
  ASSERT_EQ(field.image_names.size(), 40u);
  EXPECT_EQ(field.image_names.front(), "001.exr");
  EXPECT_EQ(field.image_names.back(), "040.exr");
  EXPECT_TRUE(field.values.allFinite());
  EXPECT_GE(field.values.minCoeff(), 0.0f);
  std::int64_t inside = 0;
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width; ++x) {
      const bool in_mask = field.mask[std::size_t(y) * field.width + x] != 0;
      inside += in_mask;
      if (in_mask) continue;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(field.values.row(field.function_index(x, y, c)).maxCoeff(), 0.0f);
    }
  // The ground disc and spheres fill much of the frame, but the corners are background.
  EXPECT_GT(inside, field.pixels() / 3);
  EXPECT_LT(inside, field.pixels());
  EXPECT_EQ(field.mask[0], 0);
}

// One camera ray per pixel so that a pixel is exactly one surface point; every light either
// lights the point, giving albedo * n.l / pi, or is below it or blocked, giving zero.
TEST(SyntheticScene, DiffusePixelsFollowLambertAndTheirShadows) {
  SynthOptions options = small_options(64, 64, 40);
  options.samples_per_axis = 1;
  const SyntheticScene scene = make_synthetic_scene(options);
  const ReflectanceField field = render_synthetic_field(options);
  const int k = sphere_of_kind(scene, SurfaceKind::diffuse);
  ASSERT_GE(k, 0);
  const SyntheticSphere& sphere = scene.spheres[k];
  const auto pixels = pixels_on_sphere(scene, options, sphere, 0.8);
  ASSERT_GT(pixels.size(), 10u);
  int lit = 0, shadowed = 0;
  for (const auto& [x, y] : pixels) {
    const Eigen::Vector2d uv = pixel_centre(scene, x, y);
    const Vector3d camera(uv.x(), uv.y(), 10);
    const double t = ray_sphere(camera, -Vector3d::UnitZ(), sphere);
    ASSERT_GT(t, 0);
    const Vector3d point = camera - t * Vector3d::UnitZ();
    const Vector3d normal = (point - sphere.center) / sphere.radius;
    for (int i = 0; i < field.lights(); ++i) {
      const Vector3d light = light_direction(field, i);
      const double cosine = normal.dot(light);
      const bool dark = cosine <= 0 || blocked(scene, point, light, k);
      lit += !dark;
      shadowed += cosine > 0 && dark;
      for (int c = 0; c < 3; ++c) {
        const double expected = dark ? 0 : sphere.material.albedo[c] * cosine / std::numbers::pi;
        EXPECT_NEAR(field.values(field.function_index(x, y, c), i), expected,
                    1e-5 + 1e-5 * expected)
            << "pixel (" << x << ", " << y << ") channel " << c << " light " << i;
      }
    }
  }
  EXPECT_GT(lit, 100);
  EXPECT_GT(shadowed, 0) << "the ground or a neighbour shadows some lights";
}

// The ground point under the centre of a sphere's shadow is dark for that light, and lit for a
// light from the other side that nothing blocks.
TEST(SyntheticScene, SpheresCastShadowsOnTheGround) {
  SynthOptions options = small_options(96, 96, 60);
  const SyntheticScene scene = make_synthetic_scene(options);
  const ReflectanceField field = render_synthetic_field(options);
  int checked = 0;
  for (int k = 0; k < int(scene.spheres.size()); ++k) {
    const SyntheticSphere& sphere = scene.spheres[k];
    for (int i = 0; i < field.lights(); ++i) {
      const Vector3d light = light_direction(field, i);
      const double rise = light.dot(scene.up);
      if (rise < 0.3 || rise > 0.85) continue;
      const Vector3d shadow = sphere.center - (sphere.radius / rise) * light;  // on the ground
      if (shadow.norm() > 0.9 * scene.ground_radius) continue;
      const int x = int(std::floor((shadow.x() - scene.camera.left) / scene.camera.pixel_size));
      const int y = int(std::floor((scene.camera.top - shadow.y()) / scene.camera.pixel_size));
      if (x < 0 || y < 0 || x >= options.width || y >= options.height) continue;
      // Skip ground pixels hidden behind or touching a sphere in the image.
      bool clear = true;
      for (const auto& s : scene.spheres)
        clear &= (pixel_centre(scene, x, y) - s.center.head<2>()).norm() >
                 s.radius + 1.5 * scene.camera.pixel_size;
      if (!clear) continue;
      // A light from the opposite side, high enough and blocked by nothing.
      const Vector3d across = light - rise * scene.up;
      int opposite = -1;
      for (int j = 0; j < field.lights(); ++j) {
        const Vector3d other = light_direction(field, j);
        const double other_rise = other.dot(scene.up);
        if (other_rise > 0.3 && (other - other_rise * scene.up).dot(across) < 0 &&
            !blocked(scene, shadow, other, -1) &&
            (opposite < 0 || other_rise > light_direction(field, opposite).dot(scene.up)))
          opposite = j;
      }
      if (opposite < 0) continue;
      const double lit_expected = scene.ground_albedo[1].minCoeff() *
                                  light_direction(field, opposite).dot(scene.up) / std::numbers::pi;
      for (int c = 0; c < 3; ++c) {
        const auto p = field.function_index(x, y, c);
        EXPECT_EQ(field.values(p, i), 0.0f) << "shadow of sphere " << k << ", light " << i;
        EXPECT_GT(field.values(p, opposite), 0.9 * lit_expected) << "light " << opposite;
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 5) << "too few shadows to check";
}

struct Highlight {
  double peak = 0;      // brightest value (green channel) over the pixels and lights
  double sharpest = 0;  // largest max/mean ratio over lights among the pixels
};

// Highlight statistics of the pixels near the centre of a sphere's image, whose normals face the
// camera, so that a broad cone of lights reaches them.
Highlight highlight(const ReflectanceField& field, const SyntheticScene& scene,
                    const SynthOptions& options, int sphere) {
  Highlight result;
  for (const auto& [x, y] : pixels_on_sphere(scene, options, scene.spheres[sphere], 0.5)) {
    const auto p = field.function_index(x, y, 1);
    const double mean = field.values.row(p).mean(), peak = field.values.row(p).maxCoeff();
    result.peak = std::max(result.peak, peak);
    if (mean > 0) result.sharpest = std::max(result.sharpest, peak / mean);
  }
  return result;
}

// Each light shows as a small, bright reflection on the near-mirror sphere (the lobe keeps its
// energy, so a narrow lobe means a high peak); the Lambertian sphere's response is broad.
TEST(SyntheticScene, NearMirrorHasSharpHighlights) {
  SynthOptions options = small_options(128, 128, 60);
  const SyntheticScene scene = make_synthetic_scene(options);
  const ReflectanceField field = render_synthetic_field(options);
  const Highlight mirror =
      highlight(field, scene, options, sphere_of_kind(scene, SurfaceKind::near_mirror));
  const Highlight glossy =
      highlight(field, scene, options, sphere_of_kind(scene, SurfaceKind::glossy));
  const Highlight diffuse =
      highlight(field, scene, options, sphere_of_kind(scene, SurfaceKind::diffuse));
  EXPECT_GT(mirror.sharpest, 6 * diffuse.sharpest)
      << "max/mean: mirror " << mirror.sharpest << ", diffuse " << diffuse.sharpest;
  EXPECT_GT(glossy.sharpest, 2 * diffuse.sharpest)
      << "max/mean: glossy " << glossy.sharpest << ", diffuse " << diffuse.sharpest;
  EXPECT_LT(diffuse.peak, 1 / std::numbers::pi);
  EXPECT_GT(glossy.peak, 2 * diffuse.peak);
  EXPECT_GT(mirror.peak, 10 * glossy.peak)
      << "peak: mirror " << mirror.peak << ", glossy " << glossy.peak;
}

TEST(SynthCommand, WritesAFolderThatLoadsBack) {
  testing::TempDir dir;
  const auto result = testing::run_relume("synth -o '" + (dir / "field").string() +
                                          "' --size 32x24 --lights 20 --seed 5");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("32x24, 20 lights"), std::string::npos) << result.output;
  const ReflectanceField loaded = load_field(dir / "field");
  SynthOptions options = small_options(32, 24, 20);
  options.seed = 5;
  const ReflectanceField rendered = render_synthetic_field(options);
  EXPECT_EQ(loaded.width, 32);
  EXPECT_EQ(loaded.height, 24);
  EXPECT_EQ(loaded.lights(), 20);
  EXPECT_TRUE(loaded.values == rendered.values);
  EXPECT_EQ(loaded.mask, rendered.mask);
  EXPECT_TRUE(loaded.directions.isApprox(rendered.directions, 1e-6f));
  EXPECT_TRUE(loaded.intensities.isOnes());
}

TEST(SynthCommand, HemisphereFlagAndBadArguments) {
  testing::TempDir dir;
  auto result = testing::run_relume("synth -o '" + (dir / "h").string() +
                                    "' --width 16 --height 12 --lights 9 --hemisphere");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const ReflectanceField loaded = load_field(dir / "h");
  EXPECT_EQ(loaded.width, 16);
  EXPECT_EQ(loaded.height, 12);
  EXPECT_GE(loaded.directions.col(2).minCoeff(), 0.0f);

  result = testing::run_relume("synth -o '" + (dir / "bad").string() + "' --lights 0");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("light count must be from 1 to 65536, got 0"), std::string::npos)
      << result.output;
  result = testing::run_relume("synth -o '" + (dir / "bad").string() + "' --size 32by32");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("'32by32'"), std::string::npos) << result.output;
  result = testing::run_relume("synth -o '" + (dir / "bad").string() + "' --size 0x10");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("0x10"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

}  // namespace
}  // namespace relume
