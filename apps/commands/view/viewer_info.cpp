// The /info document of `relume view` (docs/viewer.md): what the page needs to draw its controls
// (the field's size, its captured light directions for the hemisphere widget, the longest residual
// row for the cap slider, the maps) and the defaults a frame takes for the parameters it leaves
// out, which are `relume relight`'s.
#include <filesystem>

#include "commands/view/viewer.hpp"
#include "lighting/light_interpolation.hpp"

namespace relume {

nlohmann::ordered_json Viewer::info() const {
  nlohmann::ordered_json directions = nlohmann::ordered_json::array();
  for (int i = 0; i < field_.directions.rows(); ++i)
    directions.push_back(
        {field_.directions(i, 0), field_.directions(i, 1), field_.directions(i, 2)});
  nlohmann::ordered_json maps = nlohmann::ordered_json::array();
  for (const std::string& name : lights_.map_names())
    maps.push_back(std::filesystem::path(name).filename().string());
  // The default light: a direction, or (null) map `map`.
  nlohmann::ordered_json light, map;
  if (defaults_.light.direction)
    light = {(*defaults_.light.direction)[0], (*defaults_.light.direction)[1],
             (*defaults_.light.direction)[2]};
  else
    map = defaults_.light.map;
  const Eigen::Vector3d& color = defaults_.light.color;
  return {
      {"input", std::filesystem::path(input_).filename().string()},
      {"width", field_.width},
      {"height", field_.height},
      {"channels", field_.channels},
      {"lights", field_.lights},
      {"light_directions", directions},
      {"clusters", field_.clusters},
      {"terms", field_.terms},
      {"stored_functions", field_.stored_rows()},
      {"dark_pixels", field_.dark_pixels.size()},
      {"residual_entries_max", renderer_.longest_residual_row()},
      {"device", renderer_.device_name()},
      {"maps", maps},
      {"defaults",
       {{"light", light},
        {"map", map},
        {"rotate", defaults_.light.rotate_degrees},
        {"color", {color[0], color[1], color[2]}},
        {"spread", defaults_.light.spread_degrees},
        {"exposure", defaults_.exposure},
        {"residual", residual_cap_text(defaults_.residual_cap)},
        {"format", format_name(defaults_.format)},
        {"view", view_name(defaults_.view)}}},
      {"limits", {{"exposure", max_exposure_stops}, {"color", max_light_color}, {"spread", 90}}},
  };
}

}  // namespace relume
