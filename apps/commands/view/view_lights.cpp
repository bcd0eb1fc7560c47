// Implementation of the viewer's light vectors (view_lights.hpp).
#include "commands/view/view_lights.hpp"

#include "core/console.hpp"
#include "lighting/environment_map.hpp"

namespace relume {

ViewLights::ViewLights(const LightDirections& directions, const std::vector<std::string>& map_paths,
                       const std::string& layout) {
  try {
    interpolation_.emplace(directions);
  } catch (const Error& e) {
    interpolation_error_ = e.what();
    note("relume view: no directional lights: %s", e.what());
  }
  for (const std::string& path : map_paths) {
    const EnvironmentMap map = load_environment_map(path, parse_layout_option(layout));
    integrators_.emplace_back(map, directions);
    map_names_.push_back(path);
    note("%s: %s", path.c_str(), describe_coverage(integrators_.back().integrate(0)).c_str());
  }
}

LightRgb ViewLights::light_vector(const FrameLight& light) const {
  if (light.direction) {
    if (!interpolation_) throw BadRequest("light: " + interpolation_error_);
    return interpolation_->light_vector(
        DirectionalLight{*light.direction, light.color, light.spread_degrees});
  }
  LightRgb rgb = integrators_.at(light.map).integrate(light.rotate_degrees).rgb;
  for (int c = 0; c < 3; ++c) rgb.col(c) *= float(light.color[c]);
  return rgb;
}

bool ViewLights::covers(const Eigen::Vector3d& direction) const {
  return interpolation_ && interpolation_->covers(direction);
}

}  // namespace relume
