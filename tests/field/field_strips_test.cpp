// Tests of reading a field strip by strip (field/field_strips.hpp) and an image a band of rows at a
// time (image/image_rows.hpp): every strip equals the same rows of the whole field as load_field
// reads it (EXR and sRGB 8-bit PNG images, a mask, light intensities), strips stack back into the
// whole, tiled images are read by their tiles, and reading out of order is refused.
#include "field/field_strips.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "image/image_rows.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

// A 5-light folder of 7x10 images of `extension` with random values, a mask and intensities.
void write_random_folder(const fs::path& dir, const std::string& extension) {
  fs::create_directories(dir);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::ofstream names(dir / "filenames.txt"), directions(dir / "light_directions.txt"),
      intensities(dir / "light_intensities.txt");
  for (int i = 0; i < 5; ++i) {
    Image image(7, 10, 3);
    for (float& v : image.pixels) v = uniform(random);
    const std::string name = "light" + std::to_string(i) + extension;
    write_image(dir / name, image);
    names << name << "\n";
    directions << 0.1 * i << " 0.2 1\n";
    intensities << 1 + i << " " << 2 << " " << 0.5 + i << "\n";
  }
  Image mask(7, 10, 1);
  for (int p = 0; p < 70; ++p) mask.pixels[p] = p % 3 == 0 ? 0.0f : 1.0f;
  write_image(dir / "mask.png", mask);
}

void expect_rows_equal(const ReflectanceField& strip, const ReflectanceField& whole,
                       int first_row) {
  ASSERT_EQ(strip.width, whole.width);
  ASSERT_EQ(strip.lights(), whole.lights());
  const Eigen::Index row_functions = Eigen::Index(whole.width) * whole.channels;
  EXPECT_TRUE(strip.values ==
              whole.values.middleRows(first_row * row_functions, strip.height * row_functions));
  EXPECT_TRUE(std::equal(strip.mask.begin(), strip.mask.end(),
                         whole.mask.begin() + std::ptrdiff_t(first_row) * whole.width));
  EXPECT_EQ(strip.noise_floor, whole.noise_floor);
  EXPECT_TRUE(strip.intensities == whole.intensities);
}

TEST(FieldStrips, EveryStripEqualsTheSameRowsOfTheWholeField) {
  for (const std::string extension : {".exr", ".png"}) {
    testing::TempDir dir;
    write_random_folder(dir / "field", extension);
    const ReflectanceField whole = load_field(dir / "field");
    FieldStripReader reader(dir / "field", FieldLoadOptions{});
    EXPECT_EQ(reader.header().values.rows(), 0);
    EXPECT_EQ(reader.header().noise_floor, whole.noise_floor);
    if (extension == ".png") EXPECT_GT(whole.noise_floor, 0.0f) << "8-bit images have a floor";
    ReflectanceField stacked;
    for (int y = 0; y < 10; y += 3) {
      const ReflectanceField strip = reader.read(y, std::min(3, 10 - y));
      expect_rows_equal(strip, whole, y);
      append_field_rows(stacked, strip, 0, strip.height);
    }
    EXPECT_EQ(stacked.height, 10);
    EXPECT_TRUE(stacked.values == whole.values) << extension;
    EXPECT_EQ(stacked.mask, whole.mask);

    // Skipping rows reads forward; going back needs a rewind.
    reader.rewind();
    expect_rows_equal(reader.read(1, 2), whole, 1);
    expect_rows_equal(reader.read(6, 4), whole, 6);
    EXPECT_THROW(reader.read(2, 1), Error);
    reader.rewind();
    expect_rows_equal(reader.read(2, 1), whole, 2);
    EXPECT_THROW(reader.read(9, 2), Error) << "past the last row";
  }
}

TEST(FieldStrips, AStackedRowPicksTheRowsAsked) {
  testing::TempDir dir;
  write_random_folder(dir / "field", ".exr");
  const ReflectanceField whole = load_field(dir / "field");
  ReflectanceField picked;
  append_field_rows(picked, whole, 4, 1);
  append_field_rows(picked, whole, 8, 2);
  EXPECT_EQ(picked.height, 3);
  const Eigen::Index row = 7 * 3;
  EXPECT_TRUE(picked.values.topRows(row) == whole.values.middleRows(4 * row, row));
  EXPECT_TRUE(picked.values.bottomRows(2 * row) == whole.values.middleRows(8 * row, 2 * row));
  EXPECT_THROW(append_field_rows(picked, whole, 9, 2), Error);
}

TEST(ImageRows, TiledImagesAreReadByTheirTiles) {
  testing::TempDir dir;
  Image image(20, 37, 3);
  for (std::size_t v = 0; v < image.pixels.size(); ++v) image.pixels[v] = float(v % 101) / 7;
  auto output = OIIO::ImageOutput::create("tiled.exr");
  ASSERT_TRUE(output);
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  spec.tile_width = spec.tile_height = 16;
  const std::string path = (dir / "tiled.exr").string();
  ASSERT_TRUE(output->open(path, spec));
  ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
  ASSERT_TRUE(output->close());

  ImageRowReader reader(path, {});
  for (const auto& [first, count] : std::vector<std::pair<int, int>>{{0, 37}, {5, 13}, {30, 7}}) {
    std::vector<float> rows(std::size_t(count) * 20 * 3);
    reader.read_rows(first, count, rows.data());
    EXPECT_TRUE(
        std::equal(rows.begin(), rows.end(), image.pixels.begin() + std::ptrdiff_t(first) * 20 * 3))
        << first << " + " << count;
  }
  std::vector<float> one(20 * 3);
  EXPECT_THROW(reader.read_rows(36, 2, one.data()), Error);
  EXPECT_EQ(read_image(path).pixels, image.pixels);
}

}  // namespace
}  // namespace relume
