// Implementation of the weights' camera-domain planes (see weight_planes.hpp).
#include "model/weight_planes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <relume/error.hpp>
#include <string>

namespace relume {
namespace {

using ColourTransform = std::array<std::array<double, 3>, 3>;

// Rows: the components; columns: the channels. Orthonormal, so its inverse is its transpose.
ColourTransform fixed_colour_transform() {
  const double a = 1 / std::sqrt(3.0), b = 1 / std::sqrt(2.0), c = 1 / std::sqrt(6.0);
  return {{{a, a, a}, {b, -b, 0}, {c, c, -2 * c}}};
}

// Each term's colour transform (entry [component][channel]) for three channels; none otherwise
// (the components are the channels).
std::vector<ColourTransform> colour_transforms(const CompressedField& field) {
  if (field.channels != 3) return {};
  std::vector<ColourTransform> transforms(std::size_t(field.terms));
  const std::vector<std::int16_t>& angles = field.coded_weights.colour_angles;
  if (!angles.empty() && angles.size() != 3 * std::size_t(field.terms))
    throw Error("the weight planes' colour transforms hold " + std::to_string(angles.size()) +
                " angles, " + std::to_string(field.terms) + " terms need " +
                std::to_string(3 * field.terms));
  for (int j = 0; j < field.terms; ++j)
    transforms[std::size_t(j)] =
        angles.empty() ? fixed_colour_transform() : colour_rotation(&angles[3 * std::size_t(j)]);
  return transforms;
}

// An angle in radians as a multiple of pi / 32767.
std::int16_t angle_units(double radians) {
  return std::int16_t(std::clamp(std::lround(radians / std::numbers::pi * 32767), -32767L, 32767L));
}

std::size_t plane_values(const CompressedField& field) {
  return std::size_t(field.channels) * std::size_t(field.terms) * std::size_t(field.width) *
         std::size_t(field.height);
}

// Stored rows are taken in blocks of this many, plane by plane within a block: a row's values go
// to channels x terms planes far apart, so row by row every value touches another page.
constexpr std::size_t row_block = 512;

// Calls visit(plane, j, r, pixel, entry) for every plane (component a, term j) and every stored row
// r in [first, last) (at most row_block rows) whose channel has a non-zero entry in term j's
// component a (`transforms`: colour_transforms of the field; without any, component a is
// channel a), rows ascending.
template <typename Visit>
void for_each_plane_value(const CompressedField& field,
                          const std::vector<ColourTransform>& transforms, std::size_t first,
                          std::size_t last, Visit&& visit) {
  const int channels = field.channels, terms = field.terms;
  std::array<std::size_t, row_block> pixel;
  std::array<std::uint32_t, row_block> channel;
  for (std::size_t r = first; r < last; ++r) {
    pixel[r - first] = field.stored_function[r] / std::uint32_t(channels);
    channel[r - first] = field.stored_function[r] % std::uint32_t(channels);
  }
  for (int a = 0; a < channels; ++a)
    for (int j = 0; j < terms; ++j) {
      const double* row =
          transforms.empty() ? nullptr : transforms[std::size_t(j)][std::size_t(a)].data();
      for (std::size_t r = first; r < last; ++r)
        if (const double entry =
                row ? row[channel[r - first]] : double(int(channel[r - first]) == a);
            entry != 0)
          visit(std::size_t(a) * terms + j, j, r, pixel[r - first], entry);
    }
}

}  // namespace

std::array<std::array<double, 3>, 3> colour_rotation(const std::int16_t* angles) {
  const double unit = std::numbers::pi / 32767;
  const double a = angles[0] * unit, b = angles[1] * unit, c = angles[2] * unit;
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
               cc = std::cos(c), sc = std::sin(c);
  return {{{ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc},
           {sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc},
           {-sb, cb * sc, cb * cc}}};
}

std::vector<std::int16_t> principal_colour_angles(const CompressedField& field) {
  if (field.channels != 3) return {};
  const int terms = field.terms;
  // Each term's 3 x 3 second moments of its channels' weights, pixel by pixel (a pixel's stored
  // rows are consecutive; a channel without a row is 0).
  std::vector<Eigen::Matrix3d> moments(std::size_t(terms), Eigen::Matrix3d::Zero());
  Eigen::MatrixXd pixel_weights(3, terms);
  for (std::size_t r = 0; r < field.stored_rows();) {
    const std::uint32_t pixel = field.stored_function[r] / 3;
    pixel_weights.setZero();
    for (; r < field.stored_rows() && field.stored_function[r] / 3 == pixel; ++r)
      pixel_weights.row(field.stored_function[r] % 3) =
          field.weights.row(Eigen::Index(r)).cast<double>();
    for (int j = 0; j < terms; ++j)
      moments[std::size_t(j)] += pixel_weights.col(j) * pixel_weights.col(j).transpose();
  }
  std::vector<std::int16_t> angles;
  for (const Eigen::Matrix3d& moment : moments) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(moment);
    Eigen::Matrix3d axes =
        solver.eigenvectors().rowwise().reverse().transpose();  // strongest first
    if (solver.info() != Eigen::Success || !axes.allFinite()) axes.setIdentity();
    if (axes.determinant() < 0) axes.row(2) *= -1;  // a rotation
    // axes = Rz(a) Ry(b) Rx(c); at b = +-pi/2 only a + c or a - c is determined: a = 0 then.
    const double cos_b = std::hypot(axes(0, 0), axes(1, 0));
    const double b = std::atan2(-axes(2, 0), cos_b);
    const bool locked = cos_b < 1e-9;
    const double a = locked ? 0 : std::atan2(axes(1, 0), axes(0, 0));
    const double c =
        locked ? std::atan2(-axes(1, 2), axes(1, 1)) : std::atan2(axes(2, 1), axes(2, 2));
    for (const double angle : {a, b, c}) angles.push_back(angle_units(angle));
  }
  return angles;
}

std::vector<float> weight_planes(const CompressedField& field) {
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  std::vector<float> planes(plane_values(field), 0.0f);
  const std::vector<ColourTransform> transforms = colour_transforms(field);
  for (std::size_t first = 0; first < field.stored_rows(); first += row_block)
    for_each_plane_value(
        field, transforms, first, std::min(field.stored_rows(), first + row_block),
        [&](std::size_t plane, int j, std::size_t r, std::size_t pixel, double entry) {
          planes[plane * area + pixel] += float(entry * field.weights(Eigen::Index(r), j));
        });
  return planes;
}

void set_weights_from_integer_planes(CompressedField& field,
                                     const std::vector<std::int32_t>& samples, float step) {
  if (samples.size() != plane_values(field))
    throw Error("the weight planes hold " + std::to_string(samples.size()) + " values, a " +
                std::to_string(field.width) + "x" + std::to_string(field.height) + " field of " +
                std::to_string(field.channels) + " channels and " + std::to_string(field.terms) +
                " terms has " + std::to_string(plane_values(field)));
  const std::size_t area = std::size_t(field.width) * std::size_t(field.height);
  // Each plane value is float(sample x step), as the codestream decodes; summed over the
  // components in double, in component order, then rounded to float.
  field.weights.resize(Eigen::Index(field.stored_rows()), field.terms);
  std::vector<double> sums;
  const std::vector<ColourTransform> transforms = colour_transforms(field);
  for (std::size_t first = 0; first < field.stored_rows(); first += row_block) {
    const std::size_t last = std::min(field.stored_rows(), first + row_block);
    sums.assign((last - first) * std::size_t(field.terms), 0.0);
    for_each_plane_value(
        field, transforms, first, last,
        [&](std::size_t plane, int j, std::size_t r, std::size_t pixel, double entry) {
          const float value = float(double(samples[plane * area + pixel]) * step);
          sums[(r - first) * std::size_t(field.terms) + std::size_t(j)] += entry * double(value);
        });
    for (std::size_t r = first; r < last; ++r)
      for (int j = 0; j < field.terms; ++j)
        field.weights(Eigen::Index(r), j) =
            float(sums[(r - first) * std::size_t(field.terms) + std::size_t(j)]);
  }
}

}  // namespace relume
