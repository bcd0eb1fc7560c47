// The container writer for fields in strips (lib/container/container_strips.hpp): for any strip
// height it writes the file write_container writes for the whole field (float32, float16 and
// quantized values, dark pixels, sections larger than one coding chunk), and on failure leaves no
// file and no scratch behind.
#include "container/container_strips.hpp"

#include <gtest/gtest.h>

#include <relume/container.hpp>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "model/compressed_field_rows.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::TempDir;

// A random field where every other pixel without stored rows is inside the mask and dark, with
// a dark model.
CompressedField field_with_dark_pixels(int width, int height, int residual, std::uint64_t seed) {
  RandomFieldShape shape;
  shape.width = width;
  shape.height = height;
  shape.channels = 1;  // a third of the pixels have no stored row
  shape.lights = 24;
  shape.clusters = 5;
  shape.terms = 3;
  shape.residual_per_function = residual;
  shape.vary_residual = true;
  shape.stored_fraction = 0.7;
  shape.seed = seed;
  CompressedField field = random_compressed_field(shape);
  testing::add_dark_pixels(field);
  return field;
}

// The field without its stored rows, and strips of `rows` pixel rows cut from it.
CompressedFieldStrips strips_of(const CompressedField& field, int rows) {
  CompressedFieldStrips strips;
  strips.shell = field;
  strips.shell.stored_function.clear();
  strips.shell.cluster.clear();
  strips.shell.weights.resize(0, field.terms);
  strips.shell.residual = {};
  for (int y = 0; y < field.height; y += rows) strips.first_rows.push_back(y);
  strips.strip = [&field, rows](std::size_t s) {
    const int first = int(s) * rows;
    return compressed_rows(field, first, std::min(rows, field.height - first));
  };
  return strips;
}

// The bytes of the field `path` holds, encoded again in memory as it was stored.
std::string contents(const std::filesystem::path& path) {
  ContainerOptions stored;
  const CompressedField field = read_container(path, &stored);
  return encode_container(field, stored, "re-encoding " + path.string(), nullptr);
}

// Writes `field` whole and in strips of each height, the strips' sections coded on three threads:
// the same file, byte for byte when `same_bytes` (zstd may code a section given in pieces a few
// bytes differently from the same section given whole: then the same contents, coded alike,
// within 0.1% of the size).
void expect_same_container_for_every_strip_height(const CompressedField& field,
                                                  const ContainerOptions& options,
                                                  const std::vector<int>& heights,
                                                  bool same_bytes = true) {
  TempDir dir;
  write_container(dir / "whole.relume", field, options);
  const std::string whole = read_file(dir / "whole.relume");
  const ContainerLayout whole_layout = describe_container(dir / "whole.relume");
  ContainerOptions threaded = options;
  threaded.coding_threads = 3;
  for (const int rows : heights) {
    SCOPED_TRACE("strips of " + std::to_string(rows) + " pixel rows");
    const std::filesystem::path path = dir / ("strips_" + std::to_string(rows) + ".relume");
    const ContainerLayout layout =
        write_container_strips(path, strips_of(field, rows), threaded, dir / "scratch");
    EXPECT_TRUE(std::filesystem::is_empty(dir / "scratch"));  // the raw sections are gone
    EXPECT_EQ(layout.file_bytes, std::filesystem::file_size(path));
    if (same_bytes) {
      EXPECT_TRUE(read_file(path) == whole) << "the files differ";
      continue;
    }
    EXPECT_TRUE(contents(path) == contents(dir / "whole.relume")) << "the fields differ";
    ASSERT_EQ(layout.sections.size(), whole_layout.sections.size());
    for (std::size_t s = 0; s < layout.sections.size(); ++s) {
      const ContainerSection &a = layout.sections[s], &b = whole_layout.sections[s];
      EXPECT_EQ(a.coding, b.coding) << a.name;
      EXPECT_EQ(a.raw_bytes, b.raw_bytes) << a.name;
      EXPECT_NEAR(double(a.bytes), double(b.bytes), 0.001 * double(b.bytes)) << a.name;
    }
  }
}

TEST(ContainerStrips, WritesTheWholeFieldsBytesInFloat32AndFloat16) {
  const CompressedField field = field_with_dark_pixels(7, 6, 6, 3);
  ASSERT_FALSE(field.dark_pixels.empty());
  expect_same_container_for_every_strip_height(field, {}, {1, 2, 4, 6});
  ContainerOptions half;
  half.weights = ValuePrecision::float16;
  half.residual = ValuePrecision::float16;
  half.parameters_json = R"({"clusters": 5})";
  expect_same_container_for_every_strip_height(quantize_for_container(field, half), half, {1, 3});
}

TEST(ContainerStrips, PredictsQuantizedWeightsAcrossStripBorders) {
  // Quantized weights are stored as prediction errors from the pixels to the left and above: a
  // strip's first row is predicted from the last row of the strip above.
  const CompressedField field =
      quantize_values(field_with_dark_pixels(9, 8, 6, 4), {0.01f, 0.002f, 12});
  expect_same_container_for_every_strip_height(field, {}, {1, 2, 3, 8});
  ContainerOptions raw;
  raw.entropy_coding = false;
  expect_same_container_for_every_strip_height(field, raw, {3});
}

TEST(ContainerStrips, CodesSectionsLargerThanOneChunk) {
  // 400 x 700 pixels: the residual values (about 5 million float32 bytes) and lights span more
  // than one of the coder's 4 MiB pieces, and the delta filter carries across them.
  const CompressedField field = field_with_dark_pixels(400, 700, 12, 5);
  ASSERT_GT(field.residual.values.size() * 4, std::size_t(4) << 20);
  expect_same_container_for_every_strip_height(field, {}, {37}, false);
}

TEST(ContainerStrips, AValueThatDoesNotFitNamesItsStripAndLeavesNothing) {
  TempDir dir;
  CompressedField field = field_with_dark_pixels(5, 6, 4, 6);
  field.residual.values.back() = 1e6f;  // beyond half precision, in the last strip
  ContainerOptions half;
  half.residual = ValuePrecision::float16;
  try {
    write_container_strips(dir / "a.relume", strips_of(field, 2), half, dir / "scratch");
    ADD_FAILURE() << "a residual value of 1e6 was stored as float16";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pixel rows 4 to 6"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("65504"), std::string::npos) << e.what();
  }
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path()))
    EXPECT_TRUE(entry.is_directory()) << entry.path() << " was left behind";
}

}  // namespace
}  // namespace relume
