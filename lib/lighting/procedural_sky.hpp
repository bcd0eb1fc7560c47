// A built-in HDR environment: a lat-long sky with a small bright sun, a blue gradient that
// brightens towards the horizon, and a darker warm ground. It lets the demo and tests relight
// without any external map; the sun gives the high dynamic range real probes have.
#pragma once

#include "image/image.hpp"

namespace relume {

struct SkyOptions {
  int width = 512;                 // lat-long, height = width / 2
  double sun_elevation_deg = 35;   // above the horizon
  double sun_azimuth_deg = 30;     // about +y, from -z (straight ahead) towards +x
  double sun_radiance = 5000;      // inside the sun's disc
  double sun_radius_deg = 2.0;
};

Image render_sky(const SkyOptions& options);

}  // namespace relume
