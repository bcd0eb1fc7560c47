// What the published page needs to light a field as `relume relight` does, as manifest entries:
// the captured lights' spherical triangulation for moving a light between them
// (lighting/light_interpolation.hpp; the page computes the same barycentric and rim weights from
// it) and the thresholds of the 8-bit sRGB codes (image/srgb_codes.hpp; the page's shader counts
// them, so its codes are write_image's), and the coverage radius by which environment maps light
// it (lighting/light_vector.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <relume/field.hpp>

namespace relume {

// {"directions": distinct unit directions [x, y, z], "lights_of": per distinct direction the
//  lights (0-based) at it, "triangles": [a, b, c] into directions (counter-clockwise from
//  outside), "rim": [a, b] edges between a triangle and the uncovered part, "coverage_radius":
//  the radius within which an environment map's direction reaches its nearest light, radians}
nlohmann::ordered_json light_cover_json(const LightDirections& directions);

// The 256 thresholds of srgb_code_thresholds().
nlohmann::ordered_json srgb_thresholds_json();

}  // namespace relume
