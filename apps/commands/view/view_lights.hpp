// The light vectors of `relume view`'s frames for one field: a directional light moved between
// the captured lights (lighting/light_interpolation.hpp), or one of the --env maps integrated
// over the light set at a rotation, computed the way `relume relight --light-dir` and
// `relume relight --env MAP --rotate DEG` compute them, so frames equal their images. Each map is
// read and its pixels' directions and solid angles prepared once, when the viewer starts.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <relume/field.hpp>
#include <relume/lighting.hpp>
#include <string>
#include <vector>

#include "lighting/light_interpolation.hpp"
#include "commands/view/frame_request.hpp"

namespace relume {

class ViewLights {
 public:
  // Reads the maps (layout: a --layout value). Throws Error for an unreadable map or a light set
  // without directions; a set that cannot be triangulated leaves only the maps (directional
  // lights are then refused with the reason).
  ViewLights(const LightDirections& directions, const std::vector<std::string>& map_paths,
             const std::string& layout);

  int maps() const { return int(integrators_.size()); }
  const std::vector<std::string>& map_names() const { return map_names_; }

  // The light vector of `light` (its map index already checked). Throws BadRequest for a
  // directional light this light set cannot interpolate.
  LightRgb light_vector(const FrameLight& light) const;

  // Whether the captured lights surround `direction` (else it is lit from their cover's rim).
  bool covers(const Eigen::Vector3d& direction) const;

 private:
  std::optional<LightInterpolation> interpolation_;
  std::string interpolation_error_;  // why there is none
  std::vector<std::string> map_names_;
  std::vector<LightVectorIntegrator> integrators_;
};

}  // namespace relume
