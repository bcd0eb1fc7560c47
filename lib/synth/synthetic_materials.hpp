// Surface materials of the synthetic scenes: a Lambertian base plus an optional white,
// energy-normalised Blinn-Phong lobe, (shininess + 8) / (8 pi) * (n.h)^shininess, whose exponent
// sets diffuse, glossy or near-mirror behaviour.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace relume {

enum class SurfaceKind { diffuse, glossy, near_mirror };

struct SurfaceMaterial {
  SurfaceKind kind = SurfaceKind::diffuse;
  Eigen::Vector3d albedo = Eigen::Vector3d::Constant(0.5);  // Lambertian reflectance per channel
  double specular = 0;   // weight of the Blinn-Phong lobe (0 for diffuse)
  double shininess = 0;  // Blinn-Phong exponent
};

// Glossy: a broad highlight; near-mirror: a lobe about 2 degrees wide (in the half vector) over a
// dark base, so each light shows as a small sharp reflection.
inline constexpr double kGlossySpecular = 0.35;
inline constexpr double kGlossyShininess = 60;
inline constexpr double kNearMirrorSpecular = 0.9;
inline constexpr double kNearMirrorShininess = 1500;
inline constexpr double kNearMirrorAlbedoScale = 0.12;

// Reflected radiance per channel for unit irradiance from unit direction `light` at a point with
// unit normal `normal`: BRDF * max(0, n.l), zero for lights below the surface. `half_vector` is
// normalize(light + view), passed in because it depends on the light only.
inline Eigen::Vector3d shade(const SurfaceMaterial& material, const Eigen::Vector3d& normal,
                             const Eigen::Vector3d& light, const Eigen::Vector3d& half_vector) {
  const double cosine = normal.dot(light);
  if (cosine <= 0) return Eigen::Vector3d::Zero();
  double lobe = 0;
  if (material.specular > 0) {
    const double n_dot_h = normal.dot(half_vector);
    if (n_dot_h > 0)
      lobe = material.specular * (material.shininess + 8) / (8 * std::numbers::pi) *
             std::pow(n_dot_h, material.shininess);
  }
  return (material.albedo / std::numbers::pi + Eigen::Vector3d::Constant(lobe)) * cosine;
}

}  // namespace relume
