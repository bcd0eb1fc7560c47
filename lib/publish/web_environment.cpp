// Implementation of the published page's environment maps (web_environment.hpp).
#include "publish/web_environment.hpp"

#include <cstring>
#include <relume/lighting.hpp>
#include <vector>

#include "lighting/environment_map.hpp"
#include "publish/web_bundle.hpp"

namespace relume {

WebEnvironment lay_out_environment(const std::filesystem::path& path, int index) {
  const EnvironmentMap map = load_environment_map(path);
  const MapGeometry source = map.geometry();
  const bool kept = map.layout == EnvironmentLayout::latlong && source.width <= kept_latlong_width;
  const MapGeometry grid =
      kept ? source : MapGeometry{EnvironmentLayout::latlong, binned_width, binned_width / 2};
  std::vector<double> sums(std::size_t(grid.width) * grid.height * 3, 0.0);
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x) {
      const double solid_angle = pixel_solid_angle(source, x, y);
      if (solid_angle <= 0) continue;
      const Eigen::Vector2i cell =
          kept ? Eigen::Vector2i(x, y) : direction_to_pixel(grid, *pixel_direction(source, x, y));
      for (int c = 0; c < 3; ++c) {
        // As LightVectorIntegrator weighs a sample: the product rounded to float.
        const float energy = float(map.radiance.at(x, y, c) * solid_angle);
        sums[(std::size_t(cell.y()) * grid.width + cell.x()) * 3 + c] += energy;
      }
    }
  const std::vector<float> energies(sums.begin(), sums.end());
  std::string raw(energies.size() * sizeof(float), '\0');
  std::memcpy(raw.data(), energies.data(), raw.size());
  const std::vector<BundleArray> arrays = {{"energy", "float32", raw}};

  WebEnvironment environment;
  environment.file = {"data/env/" + std::to_string(index) + ".bin", bundle_file(arrays), -1};
  environment.entry = {{"name", path.stem().string()},
                       {"file", environment.file.path},
                       {"width", grid.width},
                       {"height", grid.height},
                       {"binned", !kept},
                       {"arrays", {{{"name", "energy"}, {"type", "float32"}}}}};
  return environment;
}

}  // namespace relume
