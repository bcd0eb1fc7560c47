// Tests of the light-file parsers on hostile input: one tokenizer for every file (several blanks
// between .lp fields, lines of only \v or \f), counts far beyond any field (2^63), coordinates
// whose squares overflow (1e200), intensities beyond float32, and numbers read the same under any
// C locale. Each refusal is a relume::Error naming the file and line.
#include <clocale>
#include <fstream>
#include <relume/error.hpp>

#include "core/text_numbers.hpp"
#include "field/light_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;
using testing::error_message;
using ::testing::HasSubstr;

fs::path write_text(const testing::TempDir& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

TEST(HostileLightFile, LpNamesSurviveSeveralBlanksBetweenFields) {
  testing::TempDir dir;
  const LpFile lp = read_lp_file(
      write_text(dir, "set.lp", "2\n  my shot 1.png \t  0   0\t\t1\nb.png\v0 1 0\f\r\n"));
  ASSERT_EQ(lp.images.size(), 2u);
  EXPECT_EQ(lp.images[0], "my shot 1.png");
  EXPECT_EQ(lp.images[1], "b.png");
  EXPECT_FLOAT_EQ(lp.directions(1, 1), 1.0f);
}

TEST(HostileLightFile, BlankLinesOfVerticalTabsAndFormFeedsAreSkipped) {
  testing::TempDir dir;
  const LpFile lp = read_lp_file(write_text(dir, "set.lp", "\v\n1\n\f\n\v \f\na.png 1 0 0\n"));
  EXPECT_EQ(lp.images.size(), 1u);
  const LightDirections rows = read_direction_rows(write_text(dir, "d.txt", "\v\n0 0 1\n\f\n"));
  EXPECT_EQ(rows.rows(), 1);
}

TEST(HostileLightFile, HugeCountsAreRefusedWithTheLine) {
  testing::TempDir dir;
  for (const std::string count :
       {"9223372036854775808", "18446744073709551616", "2147483648", "-1", "0", "1e3", "3 4"})
    EXPECT_THAT(
        error_message([&] { read_lp_file(write_text(dir, "c.lp", count + "\na 0 0 1\n")); }),
        HasSubstr("c.lp:1: expected the light count"))
        << count;
  // A count the file does not hold is refused without allocating for it.
  EXPECT_THAT(
      error_message([&] { read_lp_file(write_text(dir, "d.lp", "2000000000\na 0 0 1\n")); }),
      HasSubstr("header says 2000000000 lights but 1 light lines follow"));
}

TEST(HostileLightFile, HugeCoordinatesAreNormalisedWithoutOverflow) {
  testing::TempDir dir;
  const LightDirections d =
      read_direction_rows(write_text(dir, "d.txt", "1e200 0 1e200\n-1e308 -1e308 0\n1e-300 0 0\n"));
  EXPECT_NEAR(d(0, 0), 0.70710678f, 1e-6f);
  EXPECT_NEAR(d(0, 2), 0.70710678f, 1e-6f);
  EXPECT_NEAR(d(1, 1), -0.70710678f, 1e-6f);
  EXPECT_FLOAT_EQ(d(2, 0), 1.0f);
  EXPECT_THAT(
      error_message([&] { read_direction_rows(write_text(dir, "z.txt", "0 0 1\n0 0 0\n")); }),
      HasSubstr("z.txt:2: light direction has zero length"));
  EXPECT_THAT(error_message([&] { read_direction_rows(write_text(dir, "o.txt", "1e400 0 1\n")); }),
              HasSubstr("o.txt:1: light direction '1e400' is not finite"));
}

TEST(HostileLightFile, IntensitiesBeyondFloat32AreRefusedWhereRead) {
  testing::TempDir dir;
  EXPECT_THAT(error_message([&] {
                read_rgb_rows(write_text(dir, "i.txt", "1 1 1\n1 3.5e38 1\n"), "light intensity");
              }),
              HasSubstr("i.txt:2: light intensity"));
  EXPECT_EQ(read_rgb_rows(write_text(dir, "j.txt", "1 -3e38 1e-50\n"), "light vector")(0, 1),
            -3e38f);
}

TEST(HostileLightFile, NumbersDoNotDependOnTheLocale) {
  testing::TempDir dir;
  const auto path = write_text(dir, "d.txt", "0.6 0.8 0\n");
  // A locale with a decimal comma, where one is installed (strtod would then stop at '.').
  const char* found = nullptr;
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "ru_RU.UTF-8"})
    if ((found = std::setlocale(LC_NUMERIC, name))) break;
  const LightDirections d = read_direction_rows(path);
  std::setlocale(LC_NUMERIC, "C");
  EXPECT_FLOAT_EQ(d(0, 0), 0.6f);
  EXPECT_FLOAT_EQ(d(0, 1), 0.8f);
  if (!found) GTEST_SKIP() << "no decimal-comma locale installed; parsed under the C locale only";
}

TEST(TextNumbers, TokensAndNumbers) {
  const auto fields = split_blank_fields(" a\t\tb\v c\f\r");
  ASSERT_EQ(fields.size(), 3u);
  EXPECT_EQ(fields[2], "c");
  EXPECT_EQ(parse_number_token("+4").value, 4);
  EXPECT_EQ(parse_number_token("0,25", true).value, 0.25);
  EXPECT_EQ(parse_number_token("0,25").status, ParsedNumber::Status::not_a_number);
  EXPECT_EQ(parse_number_token("1e-400").status, ParsedNumber::Status::number);
  EXPECT_EQ(parse_number_token("-1e400").status, ParsedNumber::Status::not_finite);
  EXPECT_EQ(parse_number_token("nan").status, ParsedNumber::Status::not_finite);
  EXPECT_EQ(parse_number_token("1.5x").status, ParsedNumber::Status::not_a_number);
  EXPECT_EQ(parse_unsigned("18446744073709551615"), 18446744073709551615ull);
  EXPECT_FALSE(parse_unsigned("18446744073709551616"));
  EXPECT_FALSE(parse_unsigned("-1"));
}

}  // namespace
}  // namespace relume
