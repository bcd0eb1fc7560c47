// Tests for light-direction and RGB-row files: the field's conventions and every malformed line.
#include "field/light_file.hpp"

#include <fstream>
#include <relume/error.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {
using testing::TempDir;

std::filesystem::path write_text(const TempDir& dir, const std::string& name,
                                 const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::function<void()>& action) { return testing::error_message(action); }

TEST(LightFile, PlainRowsAreNormalised) {
  TempDir dir;
  const auto path = write_text(dir, "dirs.txt", "# comment\n0 0 2\n\n3 4 0\n");
  const LightDirections d = read_light_directions(path);
  ASSERT_EQ(d.rows(), 2);
  EXPECT_FLOAT_EQ(d(0, 2), 1.0f);
  EXPECT_FLOAT_EQ(d(1, 0), 0.6f);
  EXPECT_FLOAT_EQ(d(1, 1), 0.8f);
}

TEST(LightFile, LpWithDecimalCommasAndSpacesInNames) {
  TempDir dir;
  const auto path =
      write_text(dir, "set.lp", "2\nimg/first shot.jpg 0,6 0,8 0\nimg/b.jpg  0 0 1\n");
  const LpFile lp = read_lp_file(path);
  ASSERT_EQ(lp.images.size(), 2u);
  EXPECT_EQ(lp.images[0], "img/first shot.jpg");
  EXPECT_EQ(lp.images[1], "img/b.jpg");
  EXPECT_FLOAT_EQ(lp.directions(0, 0), 0.6f);
  EXPECT_FLOAT_EQ(lp.directions(0, 1), 0.8f);
  EXPECT_FLOAT_EQ(lp.directions(1, 2), 1.0f);
}

TEST(LightFile, RealRtiFileReads) {
  RELUME_REQUIRE_SHARED_DATA(data);
  const LpFile lp = read_lp_file(data / "olat/rti-loewenkopf/dirs.lp");
  EXPECT_EQ(lp.images.size(), 240u);
  EXPECT_NEAR(lp.directions.row(0).norm(), 1.0, 1e-6);
  EXPECT_NEAR(lp.directions(0, 2), 0.98910415, 1e-4);
}

TEST(LightFile, ErrorsNameFileLineAndValue) {
  TempDir dir;
  const auto bad_number = write_text(dir, "a.txt", "0 0 1\n0 zero 1\n");
  EXPECT_THAT(error_of([&] { read_direction_rows(bad_number); }),
              ::testing::AllOf(::testing::HasSubstr("a.txt:2"), ::testing::HasSubstr("'zero'")));
  const auto zero = write_text(dir, "b.txt", "0 0 1\n\n0 0 0\n");
  EXPECT_THAT(
      error_of([&] { read_direction_rows(zero); }),
      ::testing::AllOf(::testing::HasSubstr("b.txt:3"), ::testing::HasSubstr("zero length")));
  const auto infinite = write_text(dir, "c.txt", "0 inf 1\n");
  EXPECT_THAT(
      error_of([&] { read_direction_rows(infinite); }),
      ::testing::AllOf(::testing::HasSubstr("c.txt:1"), ::testing::HasSubstr("not finite")));
  const auto nan = write_text(dir, "d.txt", "nan 0 1\n");
  EXPECT_THAT(error_of([&] { read_direction_rows(nan); }), ::testing::HasSubstr("not finite"));
  const auto two_fields = write_text(dir, "e.txt", "0 1\n");
  EXPECT_THAT(error_of([&] { read_direction_rows(two_fields); }),
              ::testing::HasSubstr("expected 3 numbers"));
  const auto lp_count = write_text(dir, "f.lp", "3\na.jpg 0 0 1\nb.jpg 0 1 0\n");
  EXPECT_THAT(error_of([&] { read_lp_file(lp_count); }),
              ::testing::HasSubstr("header says 3 lights but 2"));
  const auto lp_header = write_text(dir, "g.lp", "three\n");
  EXPECT_THAT(error_of([&] { read_lp_file(lp_header); }), ::testing::HasSubstr("g.lp:1"));
  EXPECT_THAT(error_of([&] { read_direction_rows(dir / "missing.txt"); }),
              ::testing::HasSubstr("not found"));
}

TEST(LightFile, RgbRowsRoundTripAtFullPrecision) {
  TempDir dir;
  LightRgb rows(2, 3);
  rows << 1.0f / 3.0f, 2e-30f, -5.5f, 1e30f, 0.0f, 0.125f;
  write_rgb_rows(dir / "l.txt", rows, "test");
  const LightRgb back = read_rgb_rows(dir / "l.txt", "light vector");
  EXPECT_EQ(back, rows);
}

}  // namespace
}  // namespace relume
