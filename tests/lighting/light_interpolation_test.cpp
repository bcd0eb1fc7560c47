// Tests of moving a light between the captured ones (lighting/light_interpolation.hpp): the
// triangulation of full-sphere, hemisphere, degenerate (co-circular) and real light sets, weights
// that are one-hot at captured directions, non-negative, sum to one and reproduce the direction,
// change continuously along an orbit, fall back to the rim outside the cover, disc lights, and
// refused input.
#include "lighting/light_interpolation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <relume/error.hpp>

#include "field/light_file.hpp"
#include "support/test_support.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

using testing::error_message;
using ::testing::HasSubstr;
constexpr double pi = std::numbers::pi;

Eigen::Vector3d light(const LightDirections& directions, int i) {
  return directions.row(i).transpose().cast<double>().normalized();
}

// The 26 directions towards the faces, edges and corners of a cube: many co-circular quadruples,
// the degenerate case of a Delaunay triangulation.
LightDirections cube_directions() {
  LightDirections directions(26, 3);
  int row = 0;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z)
          directions.row(row++) = Eigen::Vector3f(float(x), float(y), float(z)).normalized();
  return directions;
}

Eigen::Vector3d orbit_direction(double elevation_degrees, double azimuth_degrees) {
  const double e = elevation_degrees * pi / 180, a = azimuth_degrees * pi / 180;
  return {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
}

// Checks every property a weight vector must have for `direction`.
void expect_valid_weights(const Eigen::VectorXd& w, int lights) {
  ASSERT_EQ(w.size(), lights);
  EXPECT_GE(w.minCoeff(), 0.0);
  EXPECT_NEAR(w.sum(), 1.0, 1e-12);
}

class LightSets : public ::testing::TestWithParam<int> {
 protected:
  LightDirections directions() const {
    switch (GetParam()) {
      case 0:
        return near_uniform_directions(253, LightLayout::sphere);
      case 1:
        return near_uniform_directions(96, LightLayout::hemisphere);
      default:
        return cube_directions();
    }
  }
};

TEST_P(LightSets, EveryLightIsACornerAndItsOwnDirectionIsOneHot) {
  const LightDirections directions = this->directions();
  const LightInterpolation interpolation(directions);
  std::vector<int> corner_count(directions.rows(), 0);
  for (const auto& t : interpolation.triangulation().triangles)
    for (int c : t) ++corner_count[c];
  for (Eigen::Index i = 0; i < directions.rows(); ++i) {
    EXPECT_GE(corner_count[i], 1) << "light " << i << " is in no triangle";
    const Eigen::VectorXd w = interpolation.weights(light(directions, int(i)));
    expect_valid_weights(w, int(directions.rows()));
    EXPECT_NEAR(w[i], 1.0, 1e-9) << "light " << i;
  }
}

TEST_P(LightSets, WeightsAreNonNegativeSumToOneAndPointAtTheDirection) {
  const LightDirections directions = this->directions();
  const LightInterpolation interpolation(directions);
  std::mt19937 random(3);
  std::normal_distribution<double> normal;
  int inside = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d d = Eigen::Vector3d(normal(random), normal(random), normal(random));
    const Eigen::VectorXd w = interpolation.weights(d);
    expect_valid_weights(w, int(directions.rows()));
    EXPECT_LE((w.array() > 0).count(), 3) << "a point light blends at most three lights";
    if (!interpolation.covers(d)) continue;
    ++inside;
    // Barycentric on the triangle's plane: sum w_i l_i is the projection of d onto it.
    Eigen::Vector3d blend = Eigen::Vector3d::Zero();
    for (Eigen::Index i = 0; i < w.size(); ++i) blend += w[i] * light(directions, int(i));
    EXPECT_LT(blend.normalized().cross(d.normalized()).norm(), 1e-9);
  }
  EXPECT_GT(inside, 500);
}

// The largest change of the weights (L1) between neighbouring points of a path, at `step`
// degrees apart; path(angle) for angle in [0, 360].
double largest_step_change(const LightInterpolation& interpolation,
                           const std::function<Eigen::Vector3d(double)>& path, double step) {
  double largest = 0;
  Eigen::VectorXd previous = interpolation.weights(path(0));
  for (double angle = step; angle <= 360; angle += step) {
    const Eigen::VectorXd w = interpolation.weights(path(angle));
    largest = std::max(largest, (w - previous).lpNorm<1>());
    previous = w;
  }
  return largest;
}

TEST_P(LightSets, ASlowOrbitChangesTheWeightsContinuously) {
  const LightInterpolation interpolation(directions());
  // A raking orbit and an arc from 120 degrees one side of the camera axis to 120 degrees the
  // other (across the rim of the hemisphere set, not through the point opposite its centre,
  // where the nearest rim point jumps): the largest change per step shrinks with the step, so
  // nothing snaps from light to light.
  const std::function<Eigen::Vector3d(double)> paths[2] = {
      [](double azimuth) { return orbit_direction(20, azimuth); },
      [](double angle) {
        const double b = (angle / 360 * 240 - 120) * pi / 180;
        return Eigen::Vector3d(0.1, std::sin(b), std::cos(b));
      }};
  for (const auto& path : paths) {
    const double coarse = largest_step_change(interpolation, path, 1.0);
    const double fine = largest_step_change(interpolation, path, 0.25);
    EXPECT_LT(coarse, 0.6);
    EXPECT_LT(fine, 0.4 * coarse);
  }
}

INSTANTIATE_TEST_SUITE_P(SphereHemisphereAndCube, LightSets, ::testing::Values(0, 1, 2));

TEST(LightInterpolation, DirectionsOutsideAHemisphereSetTakeTheNearestRimPoint) {
  const LightDirections directions = near_uniform_directions(96, LightLayout::hemisphere);
  const LightInterpolation interpolation(directions);
  EXPECT_FALSE(interpolation.triangulation().rim.empty());
  const Eigen::Vector3d behind(0.3, 0.2, -1.0);
  EXPECT_FALSE(interpolation.covers(behind));
  const Eigen::VectorXd w = interpolation.weights(behind);
  expect_valid_weights(w, 96);
  // The weighted lights are among the lowest of the set, on the side the direction leans to.
  double lowest_z = 1;
  for (int i = 0; i < 96; ++i) lowest_z = std::min(lowest_z, light(directions, i).z());
  for (int i = 0; i < 96; ++i)
    if (w[i] > 0) {
      EXPECT_LT(light(directions, i).z(), lowest_z + 0.2) << "light " << i;
      EXPECT_GT(light(directions, i).head<2>().dot(behind.head<2>()), 0) << "light " << i;
    }
}

TEST(LightInterpolation, ADiscLightSpreadsOverMoreLightsAndStillSumsToOne) {
  const LightDirections directions = near_uniform_directions(253, LightLayout::sphere);
  const LightInterpolation interpolation(directions);
  const Eigen::Vector3d d = light(directions, 17);
  const Eigen::VectorXd point = interpolation.weights(d, 0);
  const Eigen::VectorXd disc = interpolation.weights(d, 25);
  expect_valid_weights(disc, 253);
  EXPECT_GT((disc.array() > 0).count(), 10);
  EXPECT_LT(disc[17], 0.5);
  EXPECT_EQ(point[17], 1.0);
  // Lights beyond the disc (plus one triangle) get nothing.
  for (int i = 0; i < 253; ++i) {
    if (std::acos(std::clamp(light(directions, i).dot(d), -1.0, 1.0)) > 45 * pi / 180) {
      EXPECT_EQ(disc[i], 0) << "light " << i;
    }
  }
}

TEST(LightInterpolation, ColourScalesTheWeightsAndDuplicateLightsShare) {
  LightDirections directions = near_uniform_directions(40, LightLayout::sphere);
  directions.conservativeResize(41, 3);
  directions.row(40) = directions.row(5);
  const LightInterpolation interpolation(directions);
  const LightRgb rgb = interpolation.light_vector({light(directions, 5), {2, 1, 0.5}, 0});
  EXPECT_FLOAT_EQ(rgb(5, 0), 1.0f);
  EXPECT_FLOAT_EQ(rgb(40, 0), 1.0f);
  EXPECT_FLOAT_EQ(rgb(40, 2), 0.25f);
  EXPECT_FLOAT_EQ(rgb.col(1).sum(), 1.0f);
}

TEST(LightInterpolation, RealLightSetsTriangulateWithEveryLightACorner) {
  RELUME_REQUIRE_SHARED_DATA(data);
  for (const char* set : {"olat/diligent-ball-16bit", "olat/rti-loewenkopf/dirs.lp"}) {
    const LightDirections directions = read_light_directions(data / set);
    const LightInterpolation interpolation(directions);
    for (Eigen::Index i = 0; i < directions.rows(); ++i)
      EXPECT_NEAR(interpolation.weights(light(directions, int(i)))[i], 1.0, 1e-9)
          << set << " light " << i;
    // The straight-on direction lies within the captured cover of both sets.
    EXPECT_TRUE(interpolation.covers({0, 0, 1})) << set;
  }
}

// (1, 1e308, 1) overflowed to an infinite norm and a zero direction (a 500 from the viewer), and
// (1e-320, 0, 0) underflowed to "zero": they point along +y and +x.
TEST(LightInterpolation, DirectionsOfExtremeMagnitudePointWhereTheyPoint) {
  const LightInterpolation interpolation(cube_directions());
  const auto expect_near = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12) << a.transpose() << "\n" << b.transpose();
  };
  expect_near(interpolation.weights({1, 1e308, 1}), interpolation.weights({0, 1, 0}));
  expect_near(interpolation.weights({-1e308, 1e308, 0}), interpolation.weights({-1, 1, 0}));
  expect_near(interpolation.weights({1e-320, 0, 0}), interpolation.weights({1, 0, 0}));
}

TEST(LightInterpolation, BadInputIsRefused) {
  const LightDirections cube = cube_directions();
  const LightInterpolation interpolation(cube);
  EXPECT_THAT(error_message([&] { interpolation.weights({0, 0, 0}); }), HasSubstr("zero"));
  EXPECT_THAT(error_message([&] { interpolation.weights({NAN, 0, 1}); }), HasSubstr("not finite"));
  EXPECT_THAT(error_message([&] {
                interpolation.weights({0, 0, 1}, 120);
              }),
              HasSubstr("between 0 and 90"));
  EXPECT_THAT(error_message([&] {
                interpolation.light_vector({{0, 0, 1}, {1, -1, 1}, 0});
              }),
              HasSubstr("non-negative"));
  LightDirections flat(8, 3);
  for (int i = 0; i < 8; ++i)
    flat.row(i) = Eigen::Vector3f(std::cos(i * 0.7f), std::sin(i * 0.7f), 0.5f).normalized();
  EXPECT_THAT(error_message([&] { LightInterpolation{flat}; }), HasSubstr("one plane"));
  EXPECT_THAT(error_message([&] { LightInterpolation{flat.topRows(2)}; }),
              HasSubstr("at least three"));
}

}  // namespace
}  // namespace relume
