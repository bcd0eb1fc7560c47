// What one `GET /frame` of `relume view` asks for, read from its query parameters (docs/viewer.md):
//   light=x,y,z | rotate=DEG&map=I ; color=r,g,b ; spread=DEG ; exposure=E ; residual=all|N|P% ;
//   format=png|jpeg|exr ; view=image|error|mask
// Parameters left out take relume relight's defaults (FrameDefaults), so a frame equals
// `relume relight IN --env MAP --rotate DEG -o x.png` or `--light-dir x,y,z` with the same values.
// Every value is checked: a malformed, non-finite or out-of-range one, an unknown or repeated
// parameter, or a map index the viewer does not have is a BadRequest naming the parameter and
// its value (HTTP 400).
#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <relume/error.hpp>
#include <relume/relight.hpp>
#include <string>

namespace relume {

// A request the viewer refuses (HTTP 400); the message names the parameter and its value.
class BadRequest : public Error {
 public:
  using Error::Error;
};

// (frame_request.cpp names them in this order.)
enum class FrameFormat { png, jpeg, exr };
enum class FrameView { image, error, mask };

// "png", "jpeg", "exr" / "image", "error", "mask".
const char* format_name(FrameFormat format);
const char* view_name(FrameView view);
// The file extension write_image and encode_image_bytes take: ".png", ".jpg", ".exr".
const char* format_extension(FrameFormat format);
// The HTTP content type.
const char* format_content_type(FrameFormat format);

// The light of a frame: a directional light (direction set) or environment map `map` turned by
// `rotate_degrees` about the up axis; `color` scales either (a moved light's colour, as
// --light-color; a map's tint), `spread_degrees` makes the directional light a disc light.
struct FrameLight {
  std::optional<Eigen::Vector3d> direction;
  int map = 0;
  double rotate_degrees = 0;
  Eigen::Vector3d color{1, 1, 1};
  double spread_degrees = 0;
};

struct FrameRequest {
  FrameLight light;
  double exposure = 0;               // stops, for PNG and JPEG (EXR frames are linear, unexposed)
  int residual_cap = all_residual_entries;  // residual entries per function
  FrameFormat format = FrameFormat::png;
  FrameView view = FrameView::image;
};

// What the viewer has, for checking a request: the field's lights (for residual=P%) and the
// number of maps (0: directional lights only).
struct FrameLimits {
  int lights = 0;
  int maps = 0;
};

// The parameters (as HTTP gives them: a name may repeat) over `defaults`. Throws BadRequest.
FrameRequest parse_frame_request(const std::multimap<std::string, std::string>& parameters,
                                 const FrameRequest& defaults, const FrameLimits& limits);

}  // namespace relume
