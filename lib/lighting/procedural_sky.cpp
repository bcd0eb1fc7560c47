// Implementation of the procedural lat-long sky.
#include <cmath>
#include <numbers>
#include <relume/error.hpp>
#include <relume/lighting.hpp>

#include "core/memory_budget.hpp"
#include "lighting/environment_map.hpp"

namespace relume {

Image render_sky(const SkyOptions& options) {
  constexpr int max_width = 32768;  // a 32768 x 16384 map, 6 GB of float RGB
  if (options.width < 4 || options.width % 2 != 0 || options.width > max_width)
    throw Error("sky width must be an even number from 4 to " + std::to_string(max_width) +
                ", not " + std::to_string(options.width));
  check_memory_need(std::uint64_t(options.width) * std::uint64_t(options.width / 2) * 3 * 4 * 2,
                    "a sky of width " + std::to_string(options.width));
  const double to_rad = std::numbers::pi / 180;
  const double elevation = options.sun_elevation_deg * to_rad;
  const double azimuth = options.sun_azimuth_deg * to_rad;
  const Eigen::Vector3d sun(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                            -std::cos(elevation) * std::cos(azimuth));
  const double sun_cos = std::cos(options.sun_radius_deg * to_rad);
  const MapGeometry geometry{EnvironmentLayout::latlong, options.width, options.width / 2};
  Image sky(geometry.width, geometry.height, 3);
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      const Eigen::Vector3d d = *pixel_direction(geometry, x, y);
      double rgb[3];
      if (d.y() >= 0) {
        const double horizon = std::pow(1 - d.y(), 3);  // 1 at the horizon, 0 at the zenith
        rgb[0] = 0.25 + 0.75 * horizon;
        rgb[1] = 0.45 + 0.55 * horizon;
        rgb[2] = 1.0;
        const double glow = std::pow(std::max(0.0, d.dot(sun)), 64);  // halo around the sun
        for (double& v : rgb) v += 8 * glow;
      } else {
        rgb[0] = 0.20, rgb[1] = 0.15, rgb[2] = 0.10;
      }
      const bool in_sun = d.dot(sun) >= sun_cos;
      for (int c = 0; c < 3; ++c)
        sky.at(x, y, c) = static_cast<float>(in_sun ? options.sun_radiance : rgb[c]);
    }
  }
  return sky;
}

}  // namespace relume
