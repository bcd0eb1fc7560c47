// Fuzz target: environment-map layout detection and geometry. The input gives a map size (two
// 32-bit integers), a layout byte and a direction; detect_layout and check_layout_size must
// accept or refuse with an Error, and for maps they accept (small enough to walk) every pixel's
// direction must be a finite unit vector that maps back into the map, with a finite solid angle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "fuzz_support.hpp"
#include "lighting/environment_map.hpp"

namespace {

template <typename T>
T take(const std::uint8_t*& data, std::size_t& size) {
  T value{};
  const std::size_t n = std::min(size, sizeof(T));
  std::memcpy(&value, data, n);
  data += n;
  size -= n;
  return value;
}

void require(bool condition) {
  if (!condition) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace relume;
  const int width = take<std::int32_t>(data, size), height = take<std::int32_t>(data, size);
  const std::uint8_t layout_byte = take<std::uint8_t>(data, size);
  const double dx = take<double>(data, size), dy = take<double>(data, size),
               dz = take<double>(data, size);
  std::optional<EnvironmentLayout> layout;
  fuzz::expect_only_relume_errors([&] {
    if (layout_byte % 4 == 3) {
      layout = detect_layout(width, height, "fuzz map");
    } else {
      const auto chosen = static_cast<EnvironmentLayout>(layout_byte % 3);
      check_layout_size(chosen, width, height, "fuzz map");
      layout = chosen;
    }
  });
  if (!layout || std::int64_t(width) * height > 4096) return 0;
  const MapGeometry map{*layout, width, height};
  double total = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double solid_angle = pixel_solid_angle(map, x, y);
      require(std::isfinite(solid_angle) && solid_angle >= 0);
      total += solid_angle;
      const auto direction = pixel_direction(map, x, y);
      if (!direction) continue;
      require(direction->allFinite() && std::abs(direction->norm() - 1) < 1e-9);
      const Eigen::Vector2i pixel = direction_to_pixel(map, *direction);
      require(pixel.x() >= 0 && pixel.x() < width && pixel.y() >= 0 && pixel.y() < height);
    }
  // Angular pixels are integrated numerically: a 4 x 4 probe sums to 2.8% below 4 pi, 8 x 8 to
  // 0.23%, 64 x 64 to 0.008% (docs/reliability.md); 5% bounds the tiny maps.
  require(std::abs(total - 4 * M_PI) < 0.05 * 4 * M_PI);
  const Eigen::Vector3d direction(dx, dy, dz);
  if (direction.allFinite() && direction.norm() > 1e-300 && direction.norm() < 1e300) {
    const Eigen::Vector2i pixel = direction_to_pixel(map, direction);
    require(pixel.x() >= 0 && pixel.x() < width && pixel.y() >= 0 && pixel.y() < height);
  }
  return 0;
}
