// Layout detection, pixel <-> direction mappings, pixel solid angles and loading of environment
// maps (conventions in environment_map.hpp).
#include "lighting/environment_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <relume/error.hpp>
#include <relume/image.hpp>

namespace relume {
namespace {

constexpr double pi = std::numbers::pi;

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// --- angular -----------------------------------------------------------------------------------

// Disc coordinates (a right, b up, radius 1) of image position (x, y) in an angular map.
Eigen::Vector2d angular_disc_position(const MapGeometry& map, double x, double y) {
  return {2.0 * x / map.width - 1.0, 1.0 - 2.0 * y / map.height};
}

std::optional<Eigen::Vector3d> angular_direction(double a, double b) {
  const double r = std::hypot(a, b);
  if (r > 1.0) return std::nullopt;
  if (r == 0.0) return Eigen::Vector3d(0, 0, -1);
  const double theta = pi * r;
  const double s = std::sin(theta) / r;
  return Eigen::Vector3d(a * s, b * s, -std::cos(theta));
}

// Solid angle per unit disc area at radius r: the map is the azimuthal equidistant projection
// theta = pi r, so dOmega = sin(theta) dtheta dphi = (pi sin(pi r) / r) r dr dphi.
double angular_jacobian(double r) { return r < 1e-12 ? pi * pi : pi * std::sin(pi * r) / r; }

bool angular_pixel_in_map(const MapGeometry& map, int px, int py) {
  const Eigen::Vector2d c = angular_disc_position(map, px + 0.5, py + 0.5);
  return c.norm() <= 1.0;
}

double angular_pixel_solid_angle(const MapGeometry& map, int px, int py) {
  if (!angular_pixel_in_map(map, px, py)) return 0.0;
  const double step_a = 2.0 / map.width;
  const double step_b = 2.0 / map.height;
  const Eigen::Vector2d centre = angular_disc_position(map, px + 0.5, py + 0.5);
  const double far_a = std::abs(centre.x()) + step_a / 2;
  const double far_b = std::abs(centre.y()) + step_b / 2;
  if (far_a * far_a + far_b * far_b <= 1.0) {
    // Wholly inside the disc, where the Jacobian is smooth: 2 x 2 Gauss-Legendre points.
    const double g = 0.5 / std::sqrt(3.0);
    double sum = 0;
    for (double sa : {-g, g})
      for (double sb : {-g, g})
        sum += angular_jacobian(std::hypot(centre.x() + sa * step_a, centre.y() + sb * step_b));
    return sum / 4.0 * step_a * step_b;
  }
  // Crossed by the rim: midpoint rule on a 16 x 16 grid, counting only points inside the disc.
  constexpr int n = 16;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double a = centre.x() + ((i + 0.5) / n - 0.5) * step_a;
      const double b = centre.y() + ((j + 0.5) / n - 0.5) * step_b;
      const double r = std::hypot(a, b);
      if (r <= 1.0) sum += angular_jacobian(r);
    }
  }
  return sum / (n * n) * step_a * step_b;
}

Eigen::Vector2i angular_pixel(const MapGeometry& map, const Eigen::Vector3d& d) {
  const double theta = std::acos(std::clamp(-d.z(), -1.0, 1.0));
  const double s = std::hypot(d.x(), d.y());
  const double r = theta / pi;
  const double a = s > 0 ? d.x() / s * r : r;  // straight back (s == 0, z > 0): rim at the right
  const double b = s > 0 ? d.y() / s * r : 0.0;
  const double x = (a + 1.0) / 2.0 * map.width;
  const double y = (1.0 - b) / 2.0 * map.height;
  const int px = std::clamp(static_cast<int>(std::floor(x)), 0, map.width - 1);
  const int py = std::clamp(static_cast<int>(std::floor(y)), 0, map.height - 1);
  if (angular_pixel_in_map(map, px, py)) return {px, py};
  // The position lies on the rim in a pixel whose centre is outside the disc: take the nearest
  // pixel (by centre) that is part of the map, searching rings of growing size.
  for (int ring = 1;; ++ring) {
    Eigen::Vector2i best(-1, -1);
    double best_distance = 0;
    for (int qy = py - ring; qy <= py + ring; ++qy) {
      for (int qx = px - ring; qx <= px + ring; ++qx) {
        if (qx < 0 || qy < 0 || qx >= map.width || qy >= map.height) continue;
        if (!angular_pixel_in_map(map, qx, qy)) continue;
        const double distance = std::hypot(qx + 0.5 - x, qy + 0.5 - y);
        if (best.x() < 0 || distance < best_distance) {
          best = {qx, qy};
          best_distance = distance;
        }
      }
    }
    if (best.x() >= 0) return best;
  }
}

// --- vertical cross ----------------------------------------------------------------------------

struct CrossFace {
  int column;
  int row;
};

// Face cells in the order +x, -x, +y, -y, +z, -z.
constexpr std::array<CrossFace, 6> cross_faces{{{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 3}, {1, 1}}};

// Unnormalised direction of face coordinates (a right, b up) on the face in cell (column, row).
std::optional<Eigen::Vector3d> cross_face_direction(int column, int row, double a, double b) {
  if (column == 1 && row == 0) return Eigen::Vector3d(a, 1, b);    // +y
  if (column == 0 && row == 1) return Eigen::Vector3d(-1, b, -a);  // -x
  if (column == 1 && row == 1) return Eigen::Vector3d(a, b, -1);   // -z
  if (column == 2 && row == 1) return Eigen::Vector3d(1, b, a);    // +x
  if (column == 1 && row == 2) return Eigen::Vector3d(a, -1, -b);  // -y
  if (column == 1 && row == 3) return Eigen::Vector3d(a, -b, 1);   // +z
  return std::nullopt;
}

std::optional<Eigen::Vector3d> cross_direction(const MapGeometry& map, double x, double y) {
  const double face = map.width / 3.0;
  const int column = static_cast<int>(std::floor(x / face));
  const int row = static_cast<int>(std::floor(y / face));
  const double a = 2.0 * (x / face - column) - 1.0;
  const double b = 1.0 - 2.0 * (y / face - row);
  const auto d = cross_face_direction(column, row, a, b);
  if (!d) return std::nullopt;
  return d->normalized();
}

// Integral of the solid angle over the face rectangle [0, a] x [0, b] (unit distance to the face).
double cube_area_element(double a, double b) {
  return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0));
}

double cross_pixel_solid_angle(const MapGeometry& map, int px, int py) {
  const int face = map.width / 3;
  if (!cross_face_direction(px / face, py / face, 0, 0)) return 0.0;
  const int fx = px % face;
  const int fy = py % face;
  const double a0 = 2.0 * fx / face - 1.0, a1 = 2.0 * (fx + 1) / face - 1.0;
  const double b0 = 2.0 * fy / face - 1.0, b1 = 2.0 * (fy + 1) / face - 1.0;
  return std::abs(cube_area_element(a0, b0) - cube_area_element(a0, b1) -
                  cube_area_element(a1, b0) + cube_area_element(a1, b1));
}

Eigen::Vector2i cross_pixel(const MapGeometry& map, const Eigen::Vector3d& d) {
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int face_index;  // into cross_faces
  double a, b;
  if (ay >= ax && ay >= az) {
    face_index = d.y() > 0 ? 2 : 3;
    a = d.x() / ay;
    b = d.y() > 0 ? d.z() / ay : -d.z() / ay;
  } else if (ax >= az) {
    face_index = d.x() > 0 ? 0 : 1;
    a = d.x() > 0 ? d.z() / ax : -d.z() / ax;
    b = d.y() / ax;
  } else {
    face_index = d.z() > 0 ? 4 : 5;
    a = d.x() / az;
    b = d.z() > 0 ? -d.y() / az : d.y() / az;
  }
  const int face = map.width / 3;
  const auto pixel_in_face = [face](double t) {
    return std::clamp(static_cast<int>(std::floor(t * face)), 0, face - 1);
  };
  const CrossFace& cell = cross_faces[face_index];
  return {cell.column * face + pixel_in_face((a + 1.0) / 2.0),
          cell.row * face + pixel_in_face((1.0 - b) / 2.0)};
}

// --- lat-long ----------------------------------------------------------------------------------

Eigen::Vector3d latlong_direction(const MapGeometry& map, double x, double y) {
  const double theta = pi * y / map.height;
  const double phi = 2.0 * pi * (x / map.width - 0.5);
  return {std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta)};
}

Eigen::Vector2i latlong_pixel(const MapGeometry& map, const Eigen::Vector3d& d) {
  const double theta = std::acos(std::clamp(d.y() / d.norm(), -1.0, 1.0));
  const double phi = std::atan2(d.x(), -d.z());
  const double u = phi / (2.0 * pi) + 0.5;
  const int px = static_cast<int>(std::floor(u * map.width)) % map.width;
  const int py = std::min(static_cast<int>(std::floor(theta / pi * map.height)), map.height - 1);
  return {std::clamp(px, 0, map.width - 1), py};
}

// --- loading -----------------------------------------------------------------------------------

void check_finite(const Image& image, const std::string& name) {
  static const char* const channel_names[] = {"R", "G", "B"};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(image.at(x, y, c)))
          throw Error("environment map " + name + ": pixel (" + std::to_string(x) + ", " +
                      std::to_string(y) + ") channel " + channel_names[c] + " is " +
                      std::to_string(image.at(x, y, c)) + "; expected finite radiance");
}

// RGB from one channel (grey, replicated) or the first three.
Image rgb_channels(Image source, const std::string& name) {
  if (source.channels == 3) return source;
  if (source.channels == 2)
    throw Error("environment map " + name +
                " has 2 channels; expected grey (1) or RGB (3 or more)");
  Image rgb(source.width, source.height, 3);
  for (int y = 0; y < source.height; ++y)
    for (int x = 0; x < source.width; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = source.at(x, y, source.channels == 1 ? 0 : c);
  return rgb;
}

}  // namespace

std::string layout_name(EnvironmentLayout layout) {
  switch (layout) {
    case EnvironmentLayout::latlong:
      return "latlong";
    case EnvironmentLayout::angular:
      return "angular";
    case EnvironmentLayout::cross:
      return "cross";
  }
  return "unknown";
}

std::optional<EnvironmentLayout> parse_layout_option(const std::string& text) {
  if (text == "auto") return std::nullopt;
  for (auto layout :
       {EnvironmentLayout::latlong, EnvironmentLayout::angular, EnvironmentLayout::cross})
    if (text == layout_name(layout)) return layout;
  throw Error("unknown environment map layout '" + text +
              "'; expected auto, latlong, angular or cross");
}

EnvironmentLayout detect_layout(int width, int height, const std::string& name) {
  const std::string prefix = "environment map " + name + " (" + size_text(width, height) + "): ";
  if (width < 1 || height < 1) throw Error(prefix + "has no pixels");
  const std::int64_t w = width, h = height;  // 4 * width overflows int for wide maps
  if (w == 2 * h) return EnvironmentLayout::latlong;
  if (w == h) return EnvironmentLayout::angular;
  if (4 * w == 3 * h) return EnvironmentLayout::cross;
  struct Known {
    double ratio;
    const char* text;
    EnvironmentLayout layout;
  };
  const Known known[] = {{2.0, "2:1 (latlong)", EnvironmentLayout::latlong},
                         {1.0, "1:1 (angular)", EnvironmentLayout::angular},
                         {0.75, "3:4 (cross)", EnvironmentLayout::cross}};
  const double ratio = double(width) / height;
  for (const Known& k : known)
    if (std::abs(std::log(ratio / k.ratio)) < 0.03)
      throw Error(prefix + "aspect ratio is close to " + k.text +
                  " but not exact, so the layout is ambiguous; pass --layout " +
                  layout_name(k.layout) + " if that is what it is");
  if (3 * w == 4 * h)
    throw Error(prefix +
                "looks like a horizontal cross (4:3), which is not supported; convert it "
                "to a vertical cross (3:4), lat-long or angular map");
  throw Error(prefix +
              "unknown layout: expected aspect ratio 2:1 (latlong), 1:1 (angular mirror "
              "ball) or 3:4 (vertical cross), or pass --layout");
}

void check_layout_size(EnvironmentLayout layout, int width, int height, const std::string& name) {
  const std::string prefix = "environment map " + name + " (" + size_text(width, height) + "): ";
  if (width < 1 || height < 1) throw Error(prefix + "has no pixels");
  if (layout == EnvironmentLayout::angular && width != height)
    throw Error(prefix + "an angular map must be square");
  if (layout == EnvironmentLayout::cross && 4 * std::int64_t(width) != 3 * std::int64_t(height))
    throw Error(prefix + "a vertical cross must be 3:4 (width = 3 faces, height = 4 faces)");
  if (layout == EnvironmentLayout::latlong && width < 2)
    throw Error(prefix + "a lat-long map needs at least 2 columns");
}

std::optional<Eigen::Vector3d> image_to_direction(const MapGeometry& map, double x, double y) {
  if (x < 0 || y < 0 || x >= map.width || y >= map.height) return std::nullopt;
  switch (map.layout) {
    case EnvironmentLayout::latlong:
      return latlong_direction(map, x, y);
    case EnvironmentLayout::angular: {
      const Eigen::Vector2d p = angular_disc_position(map, x, y);
      return angular_direction(p.x(), p.y());
    }
    case EnvironmentLayout::cross:
      return cross_direction(map, x, y);
  }
  return std::nullopt;
}

std::optional<Eigen::Vector3d> pixel_direction(const MapGeometry& map, int px, int py) {
  if (map.layout == EnvironmentLayout::angular && !angular_pixel_in_map(map, px, py))
    return std::nullopt;
  return image_to_direction(map, px + 0.5, py + 0.5);
}

Eigen::Vector2i direction_to_pixel(const MapGeometry& map, const Eigen::Vector3d& direction) {
  if (!(direction.squaredNorm() > 0) || !direction.allFinite())
    throw Error("direction_to_pixel: direction must be finite and non-zero");
  const Eigen::Vector3d d = direction.normalized();
  switch (map.layout) {
    case EnvironmentLayout::latlong:
      return latlong_pixel(map, d);
    case EnvironmentLayout::angular:
      return angular_pixel(map, d);
    case EnvironmentLayout::cross:
      return cross_pixel(map, d);
  }
  return {0, 0};
}

double pixel_solid_angle(const MapGeometry& map, int px, int py) {
  switch (map.layout) {
    case EnvironmentLayout::latlong: {
      const double theta0 = pi * py / map.height;
      const double theta1 = pi * (py + 1) / map.height;
      return 2.0 * pi / map.width * (std::cos(theta0) - std::cos(theta1));
    }
    case EnvironmentLayout::angular:
      return angular_pixel_solid_angle(map, px, py);
    case EnvironmentLayout::cross:
      return cross_pixel_solid_angle(map, px, py);
  }
  return 0.0;
}

EnvironmentMap make_environment_map(Image radiance, EnvironmentLayout layout, std::string name) {
  check_layout_size(layout, radiance.width, radiance.height, name);
  EnvironmentMap map;
  map.radiance = rgb_channels(std::move(radiance), name);
  check_finite(map.radiance, name);
  map.layout = layout;
  map.name = std::move(name);
  return map;
}

EnvironmentMap load_environment_map(const std::filesystem::path& path,
                                    std::optional<EnvironmentLayout> layout) {
  Image image = read_image(path);
  const std::string name = path.string();
  const EnvironmentLayout chosen =
      layout ? *layout : detect_layout(image.width, image.height, name);
  return make_environment_map(std::move(image), chosen, name);
}

}  // namespace relume
