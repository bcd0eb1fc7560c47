// Tests of the light vector: solid-angle weights over Voronoi cells on the sphere, the up axis
// and handedness of each layout seen through the lights, rotation, hemisphere coverage, the real
// maps with real light sets, and `relume lights` on good and bad input.
#include <OpenImageIO/imageio.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/lighting.hpp>

#include "field/light_file.hpp"
#include "lighting/best_rotation.hpp"
#include "lighting/environment_map.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;

using ::testing::HasSubstr;
constexpr double pi = std::numbers::pi;

// n directions spread evenly over the sphere (Fibonacci lattice); with front_only, the n of them
// with z > 0 (towards the camera) from a lattice of 2n.
LightDirections fibonacci_directions(int n, bool front_only = false) {
  const int total = front_only ? 2 * n : n;
  const double golden = pi * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3f> kept;
  for (int i = 0; i < total; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / total;
    const double radius = std::sqrt(1.0 - z * z);
    const Eigen::Vector3f d(float(radius * std::cos(golden * i)),
                            float(radius * std::sin(golden * i)), float(z));
    if (!front_only || z > 0) kept.push_back(d);
  }
  LightDirections directions(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    directions.row(Eigen::Index(i)) = kept[i].transpose();
  return directions;
}

// The 26 directions towards the faces, edges and corners of a cube.
LightDirections cube_directions() {
  std::vector<Eigen::Vector3f> kept;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) kept.push_back(Eigen::Vector3f(float(x), float(y), float(z)).normalized());
  LightDirections directions(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    directions.row(Eigen::Index(i)) = kept[i].transpose();
  return directions;
}

int index_of(const LightDirections& directions, const Eigen::Vector3f& d) {
  const Eigen::Vector3f unit = d.normalized();
  for (Eigen::Index i = 0; i < directions.rows(); ++i)
    if ((directions.row(i).transpose() - unit).norm() < 1e-5f) return int(i);
  ADD_FAILURE() << "no light towards " << d.transpose();
  return 0;
}

EnvironmentMap constant_map(EnvironmentLayout layout, int width, int height, float value) {
  Image image(width, height, 3);
  std::fill(image.pixels.begin(), image.pixels.end(), value);
  return make_environment_map(std::move(image), layout, "constant");
}

// A black map with one bright pixel (R = 1000, G = 2000, B = 3000) at image position (x, y).
EnvironmentMap spot_map(const MapGeometry& g, int x, int y) {
  Image image(g.width, g.height, 3);
  for (int c = 0; c < 3; ++c) image.at(x, y, c) = 1000.0f * (c + 1);
  return make_environment_map(std::move(image), g.layout, "spot");
}

// The light that received the spot's energy, checking that no other light received any.
int lit_light(const LightVector& vector) {
  int lit = -1;
  for (Eigen::Index i = 0; i < vector.rgb.rows(); ++i) {
    if (vector.rgb(i, 0) == 0) continue;
    EXPECT_EQ(lit, -1) << "more than one light received energy";
    lit = int(i);
  }
  return lit;
}

const MapGeometry kLayouts[] = {{EnvironmentLayout::latlong, 512, 256},
                                {EnvironmentLayout::angular, 512, 512},
                                {EnvironmentLayout::cross, 384, 512}};

TEST(LightVector, ConstantMapWeightsSumToFourPiForAFullSphereLightSet) {
  const LightDirections lights = fibonacci_directions(256);
  for (const MapGeometry& g : kLayouts) {
    const LightVector v =
        integrate_light_vector(constant_map(g.layout, g.width, g.height, 1.0f), lights, 0.0);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(v.rgb.col(c).cast<double>().sum(), 4 * pi, 4 * pi * 0.005)
          << layout_name(g.layout);
    EXPECT_NEAR(v.energy_total, 4 * pi, 4 * pi * 0.005);
    EXPECT_EQ(v.energy_outside, 0.0) << layout_name(g.layout);
    // Even cells: each light's weight is near 4 pi / 256 (Fibonacci cells differ by a few %).
    EXPECT_NEAR(v.rgb.col(0).minCoeff(), 4 * pi / 256, 4 * pi / 256 * 0.25);
    EXPECT_NEAR(v.rgb.col(0).maxCoeff(), 4 * pi / 256, 4 * pi / 256 * 0.25);
  }
}

// Reference integration: every pixel against every light (no grid), in the same frame.
std::vector<double> brute_force_red(const EnvironmentMap& map, const LightDirections& lights,
                                    double rotate_degrees, double coverage) {
  const MapGeometry g = map.geometry();
  const Eigen::Matrix3d back = rotation_about_up(-rotate_degrees);
  std::vector<double> red(lights.rows(), 0.0);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const auto d = pixel_direction(g, x, y);
      if (!d) continue;
      int best = 0;
      double best_dot = -2;
      for (Eigen::Index i = 0; i < lights.rows(); ++i) {
        const double dot = d->dot(back * lights.row(i).transpose().cast<double>().normalized());
        if (dot > best_dot) best_dot = dot, best = int(i);
      }
      if (best_dot >= std::cos(coverage))
        red[best] += map.radiance.at(x, y, 0) * pixel_solid_angle(g, x, y);
    }
  return red;
}

TEST(LightVector, MatchesBruteForceNearestLightSearch) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> uniform(0.0f, 10.0f);
  for (const bool front_only : {false, true}) {
    const LightDirections lights = fibonacci_directions(97, front_only);
    for (const MapGeometry& g : {MapGeometry{EnvironmentLayout::latlong, 128, 64},
                                 MapGeometry{EnvironmentLayout::angular, 101, 101},
                                 MapGeometry{EnvironmentLayout::cross, 96, 128}}) {
      Image image(g.width, g.height, 3);
      for (float& v : image.pixels) v = uniform(random);
      const EnvironmentMap map = make_environment_map(std::move(image), g.layout, "random");
      const LightVector v = integrate_light_vector(map, lights, 37.0);
      const auto red = brute_force_red(map, lights, 37.0, v.coverage_radius);
      for (Eigen::Index i = 0; i < lights.rows(); ++i)
        EXPECT_NEAR(v.rgb(i, 0), red[i], 1e-5 * (1 + red[i]))
            << layout_name(g.layout) << " light " << i;
    }
  }
}

// Spots at hand-computed image positions (the documented axes of each layout) land on the light
// of the matching direction among the 26 cube directions.
struct Spot {
  double x, y;  // fractions of width and height
  Eigen::Vector3f direction;
};

void expect_spots_land(const MapGeometry& g, const std::vector<Spot>& spots) {
  const LightDirections lights = cube_directions();
  for (const Spot& spot : spots) {
    const int x = int(spot.x * g.width), y = int(spot.y * g.height);
    const LightVector v = integrate_light_vector(spot_map(g, x, y), lights, 0.0);
    EXPECT_EQ(lit_light(v), index_of(lights, spot.direction))
        << layout_name(g.layout) << " spot at pixel " << x << "," << y << " should light "
        << spot.direction.transpose();
  }
}

TEST(LightVectorAxes, LatlongSpotsLandOnTheDocumentedLights) {
  expect_spots_land({EnvironmentLayout::latlong, 256, 128},
                    {{0.5, 0.5, {0, 0, -1}},       // centre: forward
                     {0.75, 0.5, {1, 0, 0}},       // right
                     {0.25, 0.5, {-1, 0, 0}},      // left
                     {0.0, 0.5, {0, 0, 1}},        // edge: behind
                     {0.5, 0.02, {0, 1, 0}},       // top: up
                     {0.5, 0.98, {0, -1, 0}},      // bottom: down
                     {0.625, 0.25, {1, 1, -1}},    // right of centre and up
                     {0.875, 0.75, {1, -1, 1}}});  // right-behind and down
}

TEST(LightVectorAxes, AngularSpotsLandOnTheDocumentedLights) {
  expect_spots_land({EnvironmentLayout::angular, 256, 256},
                    {{0.5, 0.5, {0, 0, -1}},
                     {0.75, 0.5, {1, 0, 0}},
                     {0.25, 0.5, {-1, 0, 0}},
                     {0.5, 0.25, {0, 1, 0}},
                     {0.5, 0.75, {0, -1, 0}},
                     {0.99, 0.5, {0, 0, 1}},
                     {0.5 + 0.25 * 0.7071, 0.5 - 0.25 * 0.7071, {1, 1, 0}}});
}

TEST(LightVectorAxes, CrossSpotsLandOnTheDocumentedLights) {
  expect_spots_land({EnvironmentLayout::cross, 192, 256},
                    {{0.5, 0.125, {0, 1, 0}},
                     {1.0 / 6, 0.375, {-1, 0, 0}},
                     {0.5, 0.375, {0, 0, -1}},
                     {5.0 / 6, 0.375, {1, 0, 0}},
                     {0.5, 0.625, {0, -1, 0}},
                     {0.5, 0.875, {0, 0, 1}},
                     // Face corners: the back face is stored upside down, its top-right corner is
                     // (+x, -y, +z); the top face's top-left corner is (-x, +y, +z).
                     {0.66, 0.76, {1, -1, 1}},
                     {0.34, 0.01, {-1, 1, 1}},
                     {0.99, 0.26, {1, 1, 1}},
                     {0.01, 0.49, {-1, -1, 1}}});
}

TEST(LightVectorRotation, NinetyDegreesMovesEnergyToTheLightNinetyDegreesAway) {
  const LightDirections lights = cube_directions();
  for (const MapGeometry& g : kLayouts) {
    // A spot towards +x.
    const Eigen::Vector2i p = direction_to_pixel(g, {1, 0, 0});
    const EnvironmentMap map = spot_map(g, p.x(), p.y());
    const auto lit_after = [&](double degrees) {
      return lit_light(integrate_light_vector(map, lights, degrees));
    };
    EXPECT_EQ(lit_after(0), index_of(lights, {1, 0, 0})) << layout_name(g.layout);
    EXPECT_EQ(lit_after(90), index_of(lights, {0, 0, -1}))
        << layout_name(g.layout);  // R_y(90) x = -z
    EXPECT_EQ(lit_after(-90), index_of(lights, {0, 0, 1})) << layout_name(g.layout);
    EXPECT_EQ(lit_after(180), index_of(lights, {-1, 0, 0})) << layout_name(g.layout);
    EXPECT_EQ(lit_after(45), index_of(lights, {1, 0, -1})) << layout_name(g.layout);
    EXPECT_EQ(lit_after(360), index_of(lights, {1, 0, 0})) << layout_name(g.layout);
  }
}

TEST(LightVectorRotation, RotationMatrixIsRightHandedAboutUp) {
  const Eigen::Matrix3d r = rotation_about_up(90);
  EXPECT_TRUE((r * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  EXPECT_TRUE((r * Eigen::Vector3d(0, 0, 1)).isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));
  EXPECT_TRUE((r * Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

TEST(LightVectorRotation, KeepsTheEnergyOfAFullSphereLightSet) {
  const LightDirections lights = fibonacci_directions(200);
  std::mt19937 random(5);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  Image image(128, 64, 3);
  for (float& v : image.pixels) v = uniform(random);
  const EnvironmentMap map =
      make_environment_map(std::move(image), EnvironmentLayout::latlong, "r");
  const LightVector still = integrate_light_vector(map, lights, 0);
  for (double degrees : {10.0, 77.0, 200.0}) {
    const LightVector turned = integrate_light_vector(map, lights, degrees);
    EXPECT_NEAR(turned.rgb.cast<double>().sum(), still.rgb.cast<double>().sum(), 1e-4);
    EXPECT_NEAR(turned.energy_total, still.energy_total, 1e-9);
    EXPECT_GT((turned.rgb - still.rgb).norm(), 0.01 * still.rgb.norm());  // it did change
  }
}

TEST(LightVectorCoverage, FrontHemisphereLightSetLeavesAboutHalfOutside) {
  const LightDirections lights = fibonacci_directions(400, true);
  const double rho = coverage_radius(lights);
  // 400 lights over 2 pi sr: spacing about sqrt(2 pi / 400) = 7 degrees.
  EXPECT_NEAR(rho * 180 / pi, 7.0, 1.5);
  std::vector<double> outside;
  for (const MapGeometry& g : kLayouts) {
    const LightVector v =
        integrate_light_vector(constant_map(g.layout, g.width, g.height, 2.0f), lights, 0.0);
    // Covered: the front hemisphere plus a band beyond its rim that is rho wide at the rim lights
    // and narrower between them, so the outside share lies between (1 - sin rho) / 2 and 1/2.
    EXPECT_GT(v.outside_fraction(), (1 - std::sin(rho)) / 2) << layout_name(g.layout);
    EXPECT_LT(v.outside_fraction(), 0.5) << layout_name(g.layout);
    outside.push_back(v.outside_fraction());
    // Energy is conserved: covered (in the vector) + outside = total.
    EXPECT_NEAR(v.rgb.col(1).cast<double>().sum() + v.energy_outside, v.energy_total,
                1e-5 * v.energy_total);
  }
  // The three layouts integrate the same sphere (measured: 0.4686 to 0.4687).
  EXPECT_NEAR(outside[0], outside[1], 0.002);
  EXPECT_NEAR(outside[0], outside[2], 0.002);
}

// A latlong map that is bright (1) within `radius` degrees of `centre` and dark (0.001) elsewhere.
EnvironmentMap bright_patch_map(const Eigen::Vector3d& centre, double radius) {
  const MapGeometry g{EnvironmentLayout::latlong, 256, 128};
  Image image(g.width, g.height, 3);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const double angle = std::acos(std::clamp(pixel_direction(g, x, y)->dot(centre), -1.0, 1.0));
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = angle < radius * pi / 180 ? 1.0f : 0.001f;
    }
  return make_environment_map(std::move(image), g.layout, "patch");
}

TEST(LightVectorCoverage, TheBestRotationTurnsTheBrightPartOntoTheLights) {
  // Lights within 37 degrees of +z; the bright part of the map (20 degrees wide) towards +x,
  // which R_y(270) turns to +z.
  const LightDirections front = fibonacci_directions(400, true);
  std::vector<Eigen::Index> cap;
  for (Eigen::Index i = 0; i < front.rows(); ++i)
    if (front(i, 2) > 0.8f) cap.push_back(i);
  const LightDirections lights = front(cap, Eigen::all);
  const LightVectorIntegrator integrator(bright_patch_map({1, 0, 0}, 20), lights);
  const BestRotation best = find_best_rotation(integrator);
  EXPECT_GT(integrator.integrate(0).outside_fraction(), 0.9);
  EXPECT_LT(best.outside_fraction, 0.5 * integrator.integrate(0).outside_fraction());
  EXPECT_DOUBLE_EQ(best.outside_fraction, integrator.integrate(best.degrees).outside_fraction());
  EXPECT_NEAR(best.degrees, 270, 20);
  // No whole degree of the turn does clearly better (the search tries 80 of them).
  for (int degrees = 0; degrees < 360; ++degrees)
    EXPECT_GE(integrator.integrate(degrees).outside_fraction(), best.outside_fraction - 0.01)
        << degrees;
}

TEST(LightVectorCoverage, RadiusIsTheMedianSpacing) {
  EXPECT_NEAR(coverage_radius(cube_directions()) * 180 / pi, 35.26, 0.01);  // face to corner/edge
  LightDirections one(1, 3);
  one << 0, 0, 1;
  EXPECT_DOUBLE_EQ(coverage_radius(one), pi);
}

TEST(LightVectorBadInput, RefusesEmptyZeroAndNonFinite) {
  const EnvironmentMap map = constant_map(EnvironmentLayout::latlong, 16, 8, 1);
  EXPECT_THAT(error_message([&] { integrate_light_vector(map, LightDirections(0, 3), 0); }),
              HasSubstr("empty"));
  LightDirections zero(2, 3);
  zero << 0, 0, 1, 0, 0, 0;
  EXPECT_THAT(error_message([&] { integrate_light_vector(map, zero, 0); }), HasSubstr("light 2"));
  EXPECT_THAT(error_message([&] {
                integrate_light_vector(map, cube_directions(),
                                       std::numeric_limits<double>::quiet_NaN());
              }),
              HasSubstr("rotation"));
}

TEST(LightVectorRealData, DiligentLightsUnderTheSharedMaps) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const LightDirections diligent = read_light_directions(data / "olat" / "diligent-ball-16bit");
  ASSERT_EQ(diligent.rows(), 96);
  const LightDirections sphere = fibonacci_directions(500);
  for (const char* file : {"grace_cross.hdr", "rnl_probe.hdr", "uffizi_latlong_256x128.hdr",
                           "polyhaven_sunset_512x256.exr"}) {
    const EnvironmentMap map = load_environment_map(data / "envmaps" / file, std::nullopt);
    const LightVector front = integrate_light_vector(map, diligent, 0.0);
    ASSERT_EQ(front.rgb.rows(), 96);
    EXPECT_TRUE(front.rgb.allFinite());
    EXPECT_GT(front.outside_fraction(), 0.5) << file << ": DiLiGenT lights cover a narrow cone";
    EXPECT_LT(front.outside_fraction(), 1.0) << file;
    const double covered = front.rgb.cast<double>().sum() / 3;
    EXPECT_NEAR(covered + front.energy_outside, front.energy_total, 1e-4 * front.energy_total)
        << file;
    // A full-sphere set takes all of the energy and sees the same total.
    const LightVector all = integrate_light_vector(map, sphere, 0.0);
    EXPECT_EQ(all.energy_outside, 0.0) << file;
    EXPECT_NEAR(all.rgb.cast<double>().sum() / 3, all.energy_total, 1e-4 * all.energy_total)
        << file;
    EXPECT_DOUBLE_EQ(all.energy_total, front.energy_total) << file;
  }
}

// --- the command -------------------------------------------------------------------------------

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string axis_light_file() { return "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"; }

TEST(LightsCommand, WritesOneRowPerLightAndReportsCoverage) {
  testing::TempDir dir;
  write_text(dir / "axes.txt", axis_light_file());
  Image image(256, 128, 3);
  std::fill(image.pixels.begin(), image.pixels.end(), 1.0f);
  write_image(dir / "white.exr", image);
  const auto result = testing::run_relume("lights --dirs '" + (dir / "axes.txt").string() +
                                          "' --env '" + (dir / "white.exr").string() + "' -o '" +
                                          (dir / "lights.txt").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("0.00% of the map's energy falls outside"));
  EXPECT_THAT(result.output, HasSubstr("total energy 12.566"));  // 4 pi
  const LightRgb rows = read_rgb_rows(dir / "lights.txt", "light vector");
  ASSERT_EQ(rows.rows(), 6);
  // Six lights along the axes: each cell is a cube face, 4 pi / 6 sr (pixelised at 256 x 128).
  for (Eigen::Index i = 0; i < 6; ++i) EXPECT_NEAR(rows(i, 0), 4 * pi / 6, 0.01);
  // Without -o the rows go to stdout.
  const auto printed = testing::run_relume("lights --dirs '" + (dir / "axes.txt").string() +
                                           "' --env '" + (dir / "white.exr").string() + "'");
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  EXPECT_THAT(printed.output, HasSubstr("\n2.09"));
}

TEST(LightsCommand, RotateAutoNamesTheBestRotationAndObeysQuiet) {
  testing::TempDir dir;
  write_text(dir / "front.txt", "0 0 1\n0.3 0 1\n-0.3 0 1\n0 0.3 1\n0 -0.3 1\n");
  write_image(dir / "patch.exr", bright_patch_map({1, 0, 0}, 30).radiance);
  const std::string base = "lights --dirs '" + (dir / "front.txt").string() + "' --env '" +
                           (dir / "patch.exr").string() + "'";
  const auto fixed = testing::run_relume(base + " -o '" + (dir / "fixed.txt").string() + "'");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.output;
  EXPECT_THAT(fixed.output, HasSubstr("would leave")) << "the better rotation is named";
  const auto automatic =
      testing::run_relume(base + " --rotate auto -o '" + (dir / "auto.txt").string() + "'");
  ASSERT_EQ(automatic.exit_code, 0) << automatic.output;
  EXPECT_THAT(automatic.output, HasSubstr("--rotate auto chose"));
  // The auto rows carry more of the map than the unrotated ones.
  EXPECT_GT(read_rgb_rows(dir / "auto.txt", "light vector").sum(),
            2 * read_rgb_rows(dir / "fixed.txt", "light vector").sum());
  const auto quiet =
      testing::run_relume("-q " + base + " --rotate auto -o '" + (dir / "q.txt").string() + "'");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  const auto bad = testing::run_relume(base + " --rotate sideways");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_THAT(bad.output, HasSubstr("sideways"));
}

TEST(LightsCommand, ExitsNonZeroWithAMessageOnBadInput) {
  testing::TempDir dir;
  write_text(dir / "axes.txt", axis_light_file());
  const std::string dirs = " --dirs '" + (dir / "axes.txt").string() + "'";
  auto result =
      testing::run_relume("lights" + dirs + " --env '" + (dir / "missing.hdr").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("missing.hdr"));

  Image odd(50, 37, 3);
  write_image(dir / "odd.exr", odd);
  result = testing::run_relume("lights" + dirs + " --env '" + (dir / "odd.exr").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, AllOf(HasSubstr("odd.exr"), HasSubstr("50x37"), HasSubstr("layout")));

  {
    std::vector<float> pixels(8 * 4 * 3, 1.0f);
    pixels[(1 * 8 + 6) * 3] = std::numeric_limits<float>::infinity();
    auto output = OIIO::ImageOutput::create((dir / "inf.exr").string());
    ASSERT_TRUE(output);
    ASSERT_TRUE(
        output->open((dir / "inf.exr").string(), OIIO::ImageSpec(8, 4, 3, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(output->close());
  }
  result = testing::run_relume("lights" + dirs + " --env '" + (dir / "inf.exr").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, AllOf(HasSubstr("inf.exr"), HasSubstr("pixel (6, 1) channel R")));

  result = testing::run_relume("lights" + dirs + " --env '" + (dir / "odd.exr").string() +
                               "' --layout sphere");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("sphere"));
}

}  // namespace
}  // namespace relume
