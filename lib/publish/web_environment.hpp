// Environment maps for the published page, which lights the field with them at any rotation as
// `relume relight --env MAP --rotate DEG` does (lighting/light_vector.cpp): every sample of the
// map (a direction and its radiance x solid angle) goes to the nearest light within the light
// set's coverage radius. The page gets the samples as a lat-long grid of energies (radiance x
// solid angle, RGB float32) and computes each cell's direction itself (the lat-long formula of
// lighting/environment_map.hpp, at the cell's centre). A lat-long map at most
// `kept_latlong_width` pixels wide keeps its own pixels, so the page's light vector is
// relight's; any other map is binned into a `binned_width` x binned_width / 2 grid (each map
// pixel's energy to the cell that holds its direction): the same energy, directions moved by at
// most half a cell.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "publish/web_layout.hpp"

namespace relume {

inline constexpr int kept_latlong_width = 256;
inline constexpr int binned_width = 128;

struct WebEnvironment {
  nlohmann::ordered_json entry;  // {"name", "file", "width", "height", "arrays"}
  WebFile file;                  // data/env/<index>.bin: energy float32, rows x columns x RGB
};

// Reads the map (layout from its aspect ratio, as relight's --env) and lays it out as map number
// `index`. Throws Error naming the file for an unreadable or invalid map.
WebEnvironment lay_out_environment(const std::filesystem::path& map, int index);

}  // namespace relume
