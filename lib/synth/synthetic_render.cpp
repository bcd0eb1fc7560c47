// Ray-traced OLAT rendering of the synthetic scenes (SyntheticRenderer, render_synthetic_field):
// one orthographic camera ray per sub-pixel sample, then per light a shadow ray against the spheres
// and the ground and the material's shading. Direct light only, no interreflection.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>
#include <optional>
#include <relume/error.hpp>
#include <string>

#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

struct SurfaceHit {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;
  SurfaceMaterial material;
  int sphere = -1;  // index into scene.spheres, -1 for the ground
};

// The nearest surface along the camera ray through view-plane point (u, v): the largest z.
std::optional<SurfaceHit> trace_camera_ray(const SyntheticScene& scene, const Eigen::Vector2d& uv) {
  std::optional<SurfaceHit> hit;
  double nearest_z = -INFINITY;
  const Eigen::Vector3d& up = scene.up;
  const double ground_z = -(up.x() * uv.x() + up.y() * uv.y()) / up.z();
  const Eigen::Vector3d ground_point(uv.x(), uv.y(), ground_z);
  if (ground_point.squaredNorm() <= scene.ground_radius * scene.ground_radius) {
    nearest_z = ground_z;
    SurfaceMaterial ground;
    ground.albedo = scene.ground_albedo_at(ground_point);
    hit = SurfaceHit{ground_point, up, ground, -1};
  }
  for (int k = 0; k < int(scene.spheres.size()); ++k) {
    const SyntheticSphere& sphere = scene.spheres[k];
    const Eigen::Vector2d offset = uv - sphere.center.head<2>();
    const double depth_squared = sphere.radius * sphere.radius - offset.squaredNorm();
    if (depth_squared < 0) continue;
    const double z = sphere.center.z() + std::sqrt(depth_squared);
    if (z <= nearest_z) continue;
    nearest_z = z;
    const Eigen::Vector3d point(uv.x(), uv.y(), z);
    hit = SurfaceHit{point, (point - sphere.center) / sphere.radius, sphere.material, k};
  }
  return hit;
}

// Shadow rays from one surface point towards many lights. The light-independent parts of the
// ray-sphere tests (offset from each centre, squared distance beyond the surface) are computed once
// per point; the point's own sphere is left out (it shadows exactly where n.l <= 0), and the ground
// disc can only shadow points above it, on spheres.
class ShadowRays {
 public:
  void start_at(const SyntheticScene& scene, const SurfaceHit& hit) {
    casters_.clear();
    for (int k = 0; k < int(scene.spheres.size()); ++k) {
      if (k == hit.sphere) continue;
      const SyntheticSphere& sphere = scene.spheres[k];
      const Eigen::Vector3d offset = hit.point - sphere.center;
      casters_.push_back({offset, offset.squaredNorm() - sphere.radius * sphere.radius});
    }
    point_ = hit.point;
    height_ = hit.point.dot(scene.up);
    on_sphere_ = hit.sphere >= 0;
    ground_radius_squared_ = scene.ground_radius * scene.ground_radius;
  }

  // `rise` is light.dot(scene.up).
  bool blocked(const Eigen::Vector3d& light, double rise) const {
    for (const Caster& caster : casters_) {
      const double along = caster.offset.dot(light);
      // Blocked when the sphere lies ahead and the ray passes within its radius.
      if (along < 0 && along * along > caster.outside) return true;
    }
    if (on_sphere_ && rise < 0)
      return (point_ - (height_ / rise) * light).squaredNorm() <= ground_radius_squared_;
    return false;
  }

 private:
  struct Caster {
    Eigen::Vector3d offset;  // point - centre
    double outside;          // |offset|^2 - radius^2 (> 0: spheres are disjoint)
  };
  std::vector<Caster> casters_;
  Eigen::Vector3d point_;
  double height_ = 0;
  bool on_sphere_ = false;
  double ground_radius_squared_ = 0;
};

std::string image_name(int light, int lights) {
  const int digits = std::max(3, int(std::to_string(lights).size()));
  std::string number = std::to_string(light + 1);
  return std::string(digits - number.size(), '0') + number + ".exr";
}

}  // namespace

SyntheticRenderer::SyntheticRenderer(const SynthOptions& options)
    : options_(options), scene_(make_synthetic_scene(options)) {
  header_.width = options.width;
  header_.height = options.height;
  header_.channels = 3;
  header_.directions = near_uniform_directions(options.lights, options.layout);
  header_.intensities = LightRgb::Ones(options.lights, 3);
  header_.values.resize(0, options.lights);
  for (int i = 0; i < options.lights; ++i)
    header_.image_names.push_back(image_name(i, options.lights));
  // The mask: pixels that a camera ray of any sample hits.
  header_.mask.assign(std::size_t(header_.pixels()), 0);
  const int samples = options.samples_per_axis;
  parallel_for(std::size_t(options.height), options.threads, [&](std::size_t row, unsigned) {
    const int y = static_cast<int>(row);
    for (int x = 0; x < options.width; ++x)
      for (int sample = 0; sample < samples * samples; ++sample)
        if (trace_camera_ray(scene_,
                             scene_.camera.plane_point(x + (sample % samples + 0.5) / samples,
                                                       y + (sample / samples + 0.5) / samples))) {
          header_.mask[std::size_t(y) * options.width + x] = 1;
          break;
        }
  });
}

ReflectanceField SyntheticRenderer::render_rows(int first_row, int rows,
                                                ProgressReporter* progress) const {
  if (first_row < 0 || rows < 0 || first_row + rows > options_.height)
    throw Error("synthetic rows " + std::to_string(first_row) + " to " +
                std::to_string(first_row + rows) + " are outside its " +
                std::to_string(options_.height));
  ReflectanceField field = header_;
  field.height = rows;
  field.mask.assign(header_.mask.begin() + std::ptrdiff_t(first_row) * options_.width,
                    header_.mask.begin() + std::ptrdiff_t(first_row + rows) * options_.width);
  const int lights = options_.lights;
  field.values = RowMatrixF::Zero(field.pixels() * 3, lights);

  const Eigen::Vector3d view = Eigen::Vector3d::UnitZ();
  std::vector<Eigen::Vector3d> light_directions(lights), half_vectors(lights);
  std::vector<double> rises(lights);
  for (int i = 0; i < lights; ++i) {
    light_directions[i] = field.directions.row(i).transpose().cast<double>();
    half_vectors[i] = (light_directions[i] + view).normalized();
    rises[i] = light_directions[i].dot(scene_.up);
  }
  const int samples = options_.samples_per_axis;
  const double sample_weight = 1.0 / (samples * samples);

  parallel_for(std::size_t(rows), options_.threads, [&](std::size_t row, unsigned) {
    const int y = first_row + static_cast<int>(row);
    std::vector<Eigen::Vector3d> radiance(lights);
    ShadowRays shadow_rays;
    for (int x = 0; x < options_.width; ++x) {
      if (!field.mask[row * options_.width + x]) continue;
      std::fill(radiance.begin(), radiance.end(), Eigen::Vector3d::Zero());
      for (int sy = 0; sy < samples; ++sy) {
        for (int sx = 0; sx < samples; ++sx) {
          const auto hit = trace_camera_ray(
              scene_,
              scene_.camera.plane_point(x + (sx + 0.5) / samples, y + (sy + 0.5) / samples));
          if (!hit) continue;
          shadow_rays.start_at(scene_, *hit);
          for (int i = 0; i < lights; ++i) {
            if (hit->normal.dot(light_directions[i]) <= 0) continue;
            if (shadow_rays.blocked(light_directions[i], rises[i])) continue;
            radiance[i] += shade(hit->material, hit->normal, light_directions[i], half_vectors[i]);
          }
        }
      }
      for (int c = 0; c < 3; ++c) {
        float* values = field.values.row(field.function_index(x, int(row), c)).data();
        for (int i = 0; i < lights; ++i) values[i] = float(radiance[i][c] * sample_weight);
      }
    }
    if (progress) progress->advance();
  });
  return field;
}

ReflectanceField render_synthetic_field(const SynthOptions& options, ProgressReporter* progress) {
  validate_synth_options(options);
  check_memory_need(std::uint64_t(options.width) * std::uint64_t(options.height) * 3 *
                        std::uint64_t(options.lights) * sizeof(float),
                    "a synthetic field of " + std::to_string(options.width) + "x" +
                        std::to_string(options.height) + " pixels and " +
                        std::to_string(options.lights) + " lights");
  return SyntheticRenderer(options).render_rows(0, options.height, progress);
}

}  // namespace relume
