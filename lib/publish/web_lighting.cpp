// Implementation of the published page's lighting entries (web_lighting.hpp).
#include "publish/web_lighting.hpp"

#include <relume/lighting.hpp>

#include "image/srgb_codes.hpp"
#include "lighting/light_interpolation.hpp"

namespace relume {

nlohmann::ordered_json light_cover_json(const LightDirections& directions) {
  const LightInterpolation interpolation(directions);
  nlohmann::ordered_json cover;
  auto& unit = cover["directions"] = nlohmann::ordered_json::array();
  for (const Eigen::Vector3d& d : interpolation.distinct_directions())
    unit.push_back({d.x(), d.y(), d.z()});
  cover["lights_of"] = interpolation.lights_of();
  cover["triangles"] = interpolation.triangulation().triangles;
  cover["rim"] = interpolation.triangulation().rim;
  cover["coverage_radius"] = coverage_radius(directions);
  return cover;
}

nlohmann::ordered_json srgb_thresholds_json() {
  const auto& thresholds = srgb_code_thresholds();
  return nlohmann::ordered_json(std::vector<float>(thresholds.begin(), thresholds.end()));
}

}  // namespace relume
