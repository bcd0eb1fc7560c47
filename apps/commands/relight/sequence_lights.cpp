// Implementation of the frame lights of relight-sequence.
#include "commands/relight/sequence_lights.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <relume/error.hpp>

#include "core/console.hpp"
#include "field/light_file.hpp"
#include "lighting/environment_map.hpp"
#include "lighting/light_interpolation.hpp"
#include "options/rotation_option.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> read_map_list(const std::string& list) {
  std::ifstream in(list);
  if (!in) throw Error("cannot open environment list " + list);
  std::vector<std::string> maps;
  const fs::path folder = fs::path(list).parent_path();
  for (std::string line; std::getline(in, line);) {
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty() || line[0] == '#') continue;
    maps.push_back(fs::path(line).is_absolute() ? line : (folder / line).string());
  }
  if (maps.empty()) throw Error("environment list " + list + " names no maps");
  return maps;
}

// The direction of a light `elevation` degrees above the object's plane (x-y, facing the camera)
// at `azimuth` degrees from +x towards +y: counter-clockwise as the camera sees it.
Eigen::Vector3d orbit_direction(double elevation, double azimuth) {
  const double e = elevation * std::numbers::pi / 180, a = azimuth * std::numbers::pi / 180;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

// The light vectors of a moved light along an orbit or a path of directions.
std::vector<LightRgb> moved_light_frames(const SequenceOptions& options,
                                         const CompressedField& field) {
  std::vector<Eigen::Vector3d> path;
  if (!options.light_path.empty()) {
    const LightDirections rows = read_direction_rows(options.light_path);
    for (Eigen::Index i = 0; i < rows.rows(); ++i)
      path.push_back(rows.row(i).transpose().cast<double>());
    if (path.empty()) throw Error("light path " + options.light_path + " names no directions");
  } else {
    if (options.rotate_start == "auto")
      throw Error("--rotate auto turns environment maps; give --light-orbit its first azimuth");
    const double first_azimuth = parse_rotation_degrees(options.rotate_start);
    for (int frame = 0; frame < options.frames; ++frame)
      path.push_back(
          orbit_direction(*options.orbit_elevation, first_azimuth + frame * options.rotate_step));
  }
  const LightInterpolation interpolation(field.directions);
  int outside = 0;
  std::vector<LightRgb> lights;
  const Eigen::Vector3d color(options.moved_light.color.data());
  for (const auto& direction : path) {
    outside += !interpolation.covers(direction);
    lights.push_back(
        interpolation.light_vector({direction, color, options.moved_light.spread_degrees}));
  }
  if (outside > 0)
    note(
        "%d of %zu frames light the object from outside the captured lights' cover: lit from "
        "the nearest point of its rim",
        outside, path.size());
  return lights;
}

}  // namespace

std::vector<LightRgb> frame_lights(const SequenceOptions& options, const CompressedField& field) {
  if (options.orbit_elevation || !options.light_path.empty())
    return moved_light_frames(options, field);
  const auto layout = parse_layout_option(options.layout);
  std::vector<LightRgb> lights;
  if (!options.environment_list.empty()) {
    // Every map turned by the same rotation (with auto, the first map's best).
    std::optional<double> rotation;
    for (const auto& map_path : read_map_list(options.environment_list)) {
      const LightVectorIntegrator integrator(load_environment_map(map_path, layout),
                                             field.directions);
      if (!rotation) {
        const ResolvedRotation first = resolve_rotation(options.rotate_start, integrator);
        note("%s: %s", map_path.c_str(), first.information.c_str());
        rotation = first.degrees;
      }
      lights.push_back(integrator.integrate(*rotation).rgb);
    }
    return lights;
  }
  const LightVectorIntegrator integrator(load_environment_map(options.environment, layout),
                                         field.directions);
  const ResolvedRotation first = resolve_rotation(options.rotate_start, integrator);
  note("%s: %s", options.environment.c_str(), first.information.c_str());
  for (int frame = 0; frame < options.frames; ++frame)
    lights.push_back(integrator.integrate(first.degrees + frame * options.rotate_step).rgb);
  return lights;
}

}  // namespace relume
