// Tests of the .relume container: exact round trips, half precision, index widths, entropy-coded
// sections (format versions 2 and 3) and version-1 files, and refusal of truncated, altered,
// foreign and inconsistent files with messages naming the file and section. Also runs `relume
// info`.
#include "container/container.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "container/container_bytes.hpp"
#include "core/crc32.hpp"
#include "container/section_coding.hpp"
#include "core/atomic_file.hpp"
#include "field/npy.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;
using testing::TempDir;

// 6x5 pixels, 3 channels, 10 lights, 3 clusters, 2 terms; about a third of the functions are not
// stored and residual rows have 0 to 5 entries.
CompressedField sample_field(std::uint64_t seed = 7, int lights = 10) {
  RandomFieldShape shape;
  shape.width = 6;
  shape.height = 5;
  shape.channels = 3;
  shape.lights = lights;
  shape.clusters = 3;
  shape.terms = 2;
  shape.residual_per_function = 5;
  shape.vary_residual = true;
  shape.stored_fraction = 0.65;
  shape.seed = seed;
  CompressedField field = random_compressed_field(shape);
  field.mask[0] = 1;  // inside the mask yet not stored, if its functions were not drawn
  field.intensities.col(1).setConstant(0.5f);
  return field;
}

// Every member equal, floats compared bit for bit.
void expect_identical(const CompressedField& a, const CompressedField& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.channels, b.channels);
  EXPECT_EQ(a.lights, b.lights);
  EXPECT_EQ(a.terms, b.terms);
  EXPECT_EQ(a.clusters, b.clusters);
  EXPECT_EQ(a.transform, b.transform);
  EXPECT_EQ(a.mask, b.mask);
  auto same_bits = [](const float* x, const float* y, std::size_t n) {
    return std::memcmp(x, y, n * sizeof(float)) == 0;
  };
  ASSERT_EQ(a.directions.rows(), b.directions.rows());
  EXPECT_TRUE(same_bits(a.directions.data(), b.directions.data(), a.directions.size()));
  ASSERT_EQ(a.intensities.rows(), b.intensities.rows());
  EXPECT_TRUE(same_bits(a.intensities.data(), b.intensities.data(), a.intensities.size()));
  EXPECT_EQ(a.stored_function, b.stored_function);
  EXPECT_EQ(a.cluster, b.cluster);
  ASSERT_EQ(a.weights.rows(), b.weights.rows());
  ASSERT_EQ(a.weights.cols(), b.weights.cols());
  EXPECT_TRUE(same_bits(a.weights.data(), b.weights.data(), a.weights.size()));
  ASSERT_EQ(a.bases.size(), b.bases.size());
  EXPECT_TRUE(same_bits(a.bases.data(), b.bases.data(), a.bases.size()));
  EXPECT_EQ(a.residual.row_offsets, b.residual.row_offsets);
  EXPECT_EQ(a.residual.light_index, b.residual.light_index);
  ASSERT_EQ(a.residual.values.size(), b.residual.values.size());
  EXPECT_TRUE(
      same_bits(a.residual.values.data(), b.residual.values.data(), a.residual.values.size()));
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// The message of the Error that read_container throws (fails the test if none).
std::string read_error(const std::filesystem::path& path) {
  try {
    read_container(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "read_container accepted " << path;
  return {};
}

// Version 2's section table: 48-byte entries from byte 16; an entry's CRC-32 is at byte 40.
constexpr std::size_t table_start = 16, entry_bytes = 48, entry_crc = 40;

// Rewrites the section checksums and the table checksum after a test changed section contents,
// so that only the meaning of the contents is wrong.
void fix_checksums(std::string& bytes, const ContainerLayout& layout) {
  for (std::size_t s = 0; s < layout.sections.size(); ++s) {
    const ContainerSection& section = layout.sections[s];
    const std::uint32_t crc = crc32(bytes.data() + section.offset, section.bytes);
    ByteWriter encoded;
    encoded.u32(crc);
    bytes.replace(table_start + entry_bytes * s + entry_crc, 4, encoded.data());
  }
  const std::size_t table_end = table_start + entry_bytes * layout.sections.size();
  ByteWriter encoded;
  encoded.u32(crc32(bytes.data(), table_end));
  bytes.replace(table_end, 4, encoded.data());
}

TEST(Crc32, MatchesTheStandardCheckValue) {
  EXPECT_EQ(crc32(std::string_view("123456789")), 0xCBF43926u);
  EXPECT_EQ(crc32(std::string_view("")), 0u);
  EXPECT_EQ(crc32(std::string_view("6789"), crc32(std::string_view("12345"))), 0xCBF43926u);
}

TEST(Container, Float32RoundTripIsBitExact) {
  TempDir dir;
  CompressedField field = sample_field();
  ASSERT_GT(field.stored_rows(), 0u);
  ASSERT_LT(field.stored_rows(), std::size_t(field.functions()));
  ContainerOptions options;
  options.parameters_json = R"({"residual": 5, "method": "lp-dual", "lambda": 0.25})";
  write_container(dir / "a.relume", field, options);
  ContainerOptions stored;
  const CompressedField back = read_container(dir / "a.relume", &stored);
  expect_identical(field, back);
  EXPECT_EQ(stored.weights, ValuePrecision::float32);
  EXPECT_EQ(stored.residual, ValuePrecision::float32);
  EXPECT_EQ(stored.light_index, IndexWidth::bits8);  // 10 lights fit 8 bits
  EXPECT_EQ(nlohmann::json::parse(stored.parameters_json),
            nlohmann::json::parse(options.parameters_json));
}

TEST(Container, TheFileIsTheSameWhateverTheThreadsThatCodeItsSections) {
  TempDir dir;
  const CompressedField field = sample_field();
  ContainerOptions options;
  write_container(dir / "one.relume", field, options);
  options.coding_threads = 4;
  write_container(dir / "four.relume", field, options);
  EXPECT_TRUE(read_file(dir / "one.relume") == read_file(dir / "four.relume"));
  expect_identical(field, read_container(dir / "four.relume"));
}

TEST(Container, HaarTransformAndOneChannelRoundTrip) {
  TempDir dir;
  RandomFieldShape shape;
  shape.width = 4;
  shape.height = 3;
  shape.channels = 1;
  shape.lights = 7;
  shape.clusters = 1;
  shape.terms = 1;
  shape.residual_per_function = 7;
  CompressedField field = random_compressed_field(shape);
  field.transform = BasisTransform::haar;
  write_container(dir / "h.relume", field);
  expect_identical(field, read_container(dir / "h.relume"));
}

TEST(Container, HalfPrecisionRoundTripIsWithinHalfPrecision) {
  TempDir dir;
  const CompressedField field = sample_field();
  ContainerOptions options;
  options.weights = ValuePrecision::float16;
  options.residual = ValuePrecision::float16;
  write_container(dir / "h.relume", field, options);
  ContainerOptions stored;
  const CompressedField back = read_container(dir / "h.relume", &stored);
  EXPECT_EQ(stored.weights, ValuePrecision::float16);
  EXPECT_EQ(stored.residual, ValuePrecision::float16);
  // Exactly what quantize_for_container predicts; bases and everything else stay exact.
  expect_identical(quantize_for_container(field, options), back);
  // Half has an 11-bit significand: relative rounding error <= 2^-11 for normal values, absolute
  // <= 2^-25 in the subnormal range.
  const double relative = std::ldexp(1.0, -11), absolute = std::ldexp(1.0, -25);
  int changed = 0;
  for (Eigen::Index i = 0; i < field.weights.size(); ++i) {
    const float x = field.weights.data()[i], q = back.weights.data()[i];
    EXPECT_LE(std::abs(x - q), std::abs(x) * relative + absolute) << "weight " << i;
    changed += x != q;
  }
  for (std::size_t k = 0; k < field.residual.values.size(); ++k) {
    const float x = field.residual.values[k], q = back.residual.values[k];
    EXPECT_LE(std::abs(x - q), std::abs(x) * relative + absolute) << "residual " << k;
    changed += x != q;
  }
  EXPECT_GT(changed, 0);  // the values really went through half
  // Half values take 2 bytes before entropy coding.
  const ContainerLayout layout = describe_container(dir / "h.relume");
  EXPECT_EQ(layout.section("weights").raw_bytes, field.stored_rows() * field.terms * 2);
  EXPECT_EQ(layout.section("residual_values").raw_bytes, field.residual.nonzeros() * 2);
}

TEST(Container, QuantizationErrorIsZeroForFloat32AndSmallForHalf) {
  const CompressedField field = sample_field();
  const RelativeError exact = quantization_error(field, {});
  EXPECT_EQ(exact.mean, 0.0);
  EXPECT_EQ(exact.functions_averaged, std::int64_t(field.stored_rows()));
  ContainerOptions half;
  half.weights = ValuePrecision::float16;
  half.residual = ValuePrecision::float16;
  const RelativeError rounded = quantization_error(field, half);
  EXPECT_GT(rounded.mean, 0.0);
  // Squared relative error of values rounded to 11 significant bits: below (2^-11)^2 ~ 2.4e-7.
  EXPECT_LT(rounded.mean, 2.4e-7);
}

TEST(Container, HalfPrecisionRefusesValuesBeyondItsRange) {
  TempDir dir;
  CompressedField field = sample_field();
  field.weights(1, 0) = 1.0e5f;
  ContainerOptions options;
  options.weights = ValuePrecision::float16;
  try {
    write_container(dir / "big.relume", field, options);
    FAIL() << "a weight of 1e5 was stored as half";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("stored row 1 term 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("65504"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "big.relume"));
  write_container(dir / "big.relume", field);  // float32 holds it
  EXPECT_EQ(read_container(dir / "big.relume").weights(1, 0), 1.0e5f);
}

TEST(Container, LightIndexWidthIsTheSmallestThatFitsOrAsAsked) {
  EXPECT_EQ(resolve_light_index_width(IndexWidth::automatic, 256), IndexWidth::bits8);
  EXPECT_EQ(resolve_light_index_width(IndexWidth::automatic, 257), IndexWidth::bits16);
  EXPECT_EQ(resolve_light_index_width(IndexWidth::automatic, 65536), IndexWidth::bits16);
  EXPECT_EQ(resolve_light_index_width(IndexWidth::automatic, 65537), IndexWidth::bits32);
  EXPECT_EQ(resolve_light_index_width(IndexWidth::bits32, 10), IndexWidth::bits32);
  EXPECT_THROW(resolve_light_index_width(IndexWidth::bits8, 257), Error);
  EXPECT_THROW(resolve_light_index_width(IndexWidth::bits16, 65537), Error);

  TempDir dir;
  const CompressedField field = sample_field(3, 300);
  const std::size_t nnz = field.residual.nonzeros();
  ASSERT_GT(nnz, 0u);
  EXPECT_EQ(plan_container(field).section("residual_indices").raw_bytes, nnz * 2);
  ContainerOptions wide;
  wide.light_index = IndexWidth::bits32;
  write_container(dir / "wide.relume", field, wide);
  EXPECT_EQ(describe_container(dir / "wide.relume").section("residual_indices").raw_bytes, nnz * 4);
  ContainerOptions stored;
  expect_identical(field, read_container(dir / "wide.relume", &stored));
  EXPECT_EQ(stored.light_index, IndexWidth::bits32);
  ContainerOptions narrow;
  narrow.light_index = IndexWidth::bits8;
  EXPECT_THROW(write_container(dir / "narrow.relume", field, narrow), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "narrow.relume"));
}

TEST(Container, PlanMatchesTheWrittenFileAndCountsStoredBytes) {
  TempDir dir;
  const CompressedField field = sample_field();
  const ContainerLayout planned = plan_container(field);
  write_container(dir / "a.relume", field);
  const ContainerLayout written = describe_container(dir / "a.relume");
  EXPECT_EQ(planned.file_bytes, std::filesystem::file_size(dir / "a.relume"));
  EXPECT_EQ(written.file_bytes, planned.file_bytes);
  EXPECT_EQ(written.version, container_format_version);
  ASSERT_EQ(written.sections.size(), planned.sections.size());
  std::uint64_t total = written.preamble_bytes;
  for (std::size_t s = 0; s < written.sections.size(); ++s) {
    EXPECT_EQ(written.sections[s].name, planned.sections[s].name);
    EXPECT_EQ(written.sections[s].offset, planned.sections[s].offset);
    EXPECT_EQ(written.sections[s].bytes, planned.sections[s].bytes);
    EXPECT_EQ(written.sections[s].raw_bytes, planned.sections[s].raw_bytes);
    EXPECT_EQ(written.sections[s].coding, planned.sections[s].coding);
    EXPECT_EQ(written.sections[s].crc32, planned.sections[s].crc32);
    EXPECT_LE(written.sections[s].bytes, written.sections[s].raw_bytes) << "coding never grows";
    total += written.sections[s].bytes;
  }
  EXPECT_EQ(total, written.file_bytes);
  const std::size_t rows = field.stored_rows();
  EXPECT_EQ(written.section("lights").raw_bytes, std::uint64_t(field.lights) * 6 * 4);
  EXPECT_EQ(written.section("clusters").raw_bytes, rows);  // 3 clusters: one byte each
  EXPECT_EQ(written.section("bases").raw_bytes, std::uint64_t(3 * 2 * 10 * 4));
  EXPECT_EQ(written.section("weights").raw_bytes, rows * 2 * 4);
  EXPECT_EQ(written.section("residual_offsets").raw_bytes, rows);  // <= 5 entries: u8 lengths
  EXPECT_EQ(written.section("residual_indices").raw_bytes, field.residual.nonzeros());
  EXPECT_EQ(written.section("residual_values").raw_bytes, field.residual.nonzeros() * 4);
}

TEST(Container, MaskAndFunctionsUseTheSmallerOfBitmapAndRuns) {
  TempDir dir;
  // A scattered mask (bitmap is smaller) and a solid block of stored functions (runs are smaller).
  RandomFieldShape shape;
  shape.width = 64;
  shape.height = 64;
  shape.channels = 1;
  shape.lights = 4;
  shape.clusters = 2;
  shape.terms = 1;
  shape.residual_per_function = 1;
  CompressedField field = random_compressed_field(shape);
  for (std::size_t q = 0; q < field.mask.size(); ++q) field.mask[q] = (q * 7919 % 13) < 6;
  ContainerOptions raw;  // the sections' own bytes, to look at their first byte
  raw.entropy_coding = false;
  write_container(dir / "a.relume", field, raw);
  const std::string bytes = read_file(dir / "a.relume");
  const ContainerLayout layout = describe_container(dir / "a.relume");
  EXPECT_EQ(bytes[layout.section("mask").offset], 0);  // bitmap
  EXPECT_EQ(layout.section("mask").bytes, 1 + 64u * 64 / 8);
  EXPECT_EQ(bytes[layout.section("functions").offset], 1);  // runs: 0 absent, 4096 present
  EXPECT_EQ(layout.section("functions").bytes, 1u + 1 + 2);
  expect_identical(field, read_container(dir / "a.relume"));

  // And the other way round: a solid mask, scattered functions.
  std::fill(field.mask.begin(), field.mask.end(), 1);
  std::vector<std::size_t> keep;
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    if (r % 3 != 1) keep.push_back(r);
  CompressedField sparse = field;
  sparse.stored_function.clear();
  sparse.cluster.clear();
  sparse.weights.resize(Eigen::Index(keep.size()), 1);
  sparse.residual = {};
  sparse.residual.row_offsets.push_back(0);
  for (std::size_t i = 0; i < keep.size(); ++i) {
    const std::size_t r = keep[i];
    sparse.stored_function.push_back(field.stored_function[r]);
    sparse.cluster.push_back(field.cluster[r]);
    sparse.weights(Eigen::Index(i), 0) = field.weights(Eigen::Index(r), 0);
    for (std::uint32_t k = field.residual.row_offsets[r]; k < field.residual.row_offsets[r + 1];
         ++k) {
      sparse.residual.light_index.push_back(field.residual.light_index[k]);
      sparse.residual.values.push_back(field.residual.values[k]);
    }
    sparse.residual.row_offsets.push_back(std::uint32_t(sparse.residual.values.size()));
  }
  write_container(dir / "b.relume", sparse, raw);
  const std::string sparse_bytes = read_file(dir / "b.relume");
  const ContainerLayout sparse_layout = describe_container(dir / "b.relume");
  EXPECT_EQ(sparse_bytes[sparse_layout.section("mask").offset], 1);       // runs
  EXPECT_EQ(sparse_bytes[sparse_layout.section("functions").offset], 0);  // bitmap
  expect_identical(sparse, read_container(dir / "b.relume"));
}

// sample_field with dark pixels and their gains: every section holds bytes.
CompressedField sample_field_with_dark_pixels() {
  RandomFieldShape shape;
  shape.width = 10;
  shape.height = 9;
  shape.channels = 3;
  shape.lights = 10;
  shape.clusters = 3;
  shape.terms = 2;
  shape.residual_per_function = 5;
  shape.stored_fraction = 0.3;
  CompressedField field = random_compressed_field(shape);
  testing::add_dark_pixels(field);
  testing::add_dark_gains(field);
  return field;
}

TEST(Container, DarkGainsRoundTripAsOneValuePerBlock) {
  TempDir dir;
  const CompressedField field = sample_field_with_dark_pixels();
  ASSERT_FALSE(field.dark_gains.empty());
  write_container(dir / "g.relume", field);
  const CompressedField read = read_container(dir / "g.relume");
  EXPECT_EQ(read.dark_gains, field.dark_gains);
  EXPECT_EQ(read.dark_gain_step, field.dark_gain_step);
  // A gain off the step cannot be stored: refused, naming the pixel.
  CompressedField off_step = field;
  off_step.dark_gains.back() += 0.5f * off_step.dark_gain_step;
  EXPECT_THAT(testing::error_message([&] { write_container(dir / "m.relume", off_step); }),
              ::testing::HasSubstr(std::to_string(off_step.dark_pixels.back())));
}

TEST(Container, AnAlteredByteInAnySectionIsRefusedNamingTheSection) {
  TempDir dir;
  const auto path = dir / "a.relume";
  write_container(path, sample_field_with_dark_pixels());
  const std::string original = read_file(path);
  const ContainerLayout layout = describe_container(path);
  ASSERT_EQ(layout.sections.size(), 16u);
  for (const ContainerSection& section : layout.sections) {
    if (section.bytes == 0) continue;  // basis_scales of float bases: nothing to alter
    std::string altered = original;
    altered[section.offset + section.bytes / 2] ^= 0x5A;
    write_bytes(path, altered);
    const std::string message = read_error(path);
    EXPECT_NE(message.find("section '" + section.name + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("corrupt"), std::string::npos) << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_THROW(describe_container(path), Error);
  }
  // A byte of the section table itself (the 'bases' entry's size).
  std::string altered = original;
  altered[table_start + entry_bytes * 8 + 24] ^= 0x01;
  write_bytes(path, altered);
  const std::string message = read_error(path);
  EXPECT_NE(message.find("section table is corrupt"), std::string::npos) << message;
}

TEST(Container, ATruncatedFileIsRefusedNamingTheSection) {
  TempDir dir;
  const auto path = dir / "a.relume";
  write_container(path, sample_field());
  const std::string original = read_file(path);
  const ContainerLayout layout = describe_container(path);
  for (const ContainerSection& section : layout.sections) {
    if (section.bytes == 0) continue;
    write_bytes(path, original.substr(0, section.offset + section.bytes / 2));
    const std::string message = read_error(path);
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_NE(message.find("section '" + section.name + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
  for (std::size_t length : {std::size_t(10), std::size_t(100)}) {
    write_bytes(path, original.substr(0, length));
    const std::string message = read_error(path);
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  }
  write_bytes(path, original + "extra");
  EXPECT_NE(read_error(path).find("5 unexpected bytes after its last section"), std::string::npos);
}

TEST(Container, ForeignFilesWrongMagicAndVersionsGetClearErrors) {
  TempDir dir;
  const auto path = dir / "a.relume";
  write_container(path, sample_field());
  const std::string original = read_file(path);

  std::string wrong_magic = original;
  wrong_magic[3] = 'X';
  write_bytes(path, wrong_magic);
  std::string message = read_error(path);
  EXPECT_NE(message.find(path.string() + " is not a relume container"), std::string::npos)
      << message;
  EXPECT_NE(message.find("magic"), std::string::npos) << message;

  std::string version = original;
  version[8] = 7;
  write_bytes(path, version);
  message = read_error(path);
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("version 7 is not supported (this relume reads versions 1 to 6)"),
            std::string::npos)
      << message;

  const auto text = dir / "notes.relume";
  write_bytes(text, "width 6 height 5\n");
  message = read_error(text);
  EXPECT_NE(message.find(text.string() + " is not a relume container"), std::string::npos)
      << message;

  const auto png = dir / "image.png";
  write_image(png, Image(4, 4, 3));
  message = read_error(png);
  EXPECT_NE(message.find(png.string() + " is not a relume container"), std::string::npos)
      << message;

  const auto empty = dir / "empty.relume";
  write_bytes(empty, "");
  message = read_error(empty);
  EXPECT_NE(message.find(empty.string() + " is empty"), std::string::npos) << message;

  message = read_error(dir / "missing.relume");
  EXPECT_NE(message.find("container not found: " + (dir / "missing.relume").string()),
            std::string::npos)
      << message;
  message = read_error(dir.path());
  EXPECT_NE(message.find("is not a relume container"), std::string::npos) << message;
}

TEST(Container, ContentsThatContradictTheHeaderAreRefusedNamingTheSection) {
  TempDir dir;
  const auto path = dir / "a.relume";
  const CompressedField field = sample_field();
  ContainerOptions raw;  // so that the test can edit the sections' contents in place
  raw.entropy_coding = false;
  write_container(path, field, raw);
  const std::string original = read_file(path);
  const ContainerLayout layout = describe_container(path);

  auto expect_refused = [&](std::string bytes, const std::string& section,
                            const std::string& what) {
    fix_checksums(bytes, layout);
    write_bytes(path, bytes);
    const std::string message = read_error(path);
    EXPECT_NE(message.find("section '" + section + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  std::string bytes = original;
  bytes[layout.section("residual_indices").offset] = 10;  // light 10 of 10
  expect_refused(bytes, "residual_indices", "expected < 10 lights");

  bytes = original;
  bytes[layout.section("clusters").offset + 2] = 3;  // cluster 3 of 3
  expect_refused(bytes, "clusters", "expected < 3 clusters");

  bytes = original;
  const std::size_t lengths = layout.section("residual_offsets").offset;
  ++bytes[lengths];  // one more entry than the header's residual_nonzeros
  expect_refused(bytes, "residual_offsets", "residual entries");

  bytes = original;
  ByteWriter nan;
  nan.f32(std::nanf(""));
  bytes.replace(layout.section("bases").offset + 8, 4, nan.data());
  expect_refused(bytes, "bases", "expected finite");

  bytes = original;
  const std::size_t header = layout.section("header").offset;
  const std::size_t lights_key = bytes.find("\"lights\":10", header);
  ASSERT_NE(lights_key, std::string::npos);
  bytes[lights_key + 10] = '9';  // "lights":19: the lights section is now the wrong size
  expect_refused(bytes, "lights", "the header implies");

  // More stored rows than the per-row sections hold: refused by their sizes, before the functions
  // set is decoded (the sizes bound what a crafted header can make the reader allocate).
  bytes = original;
  const std::size_t rows_key = bytes.find("\"stored_rows\":", header);
  ASSERT_NE(rows_key, std::string::npos);
  ASSERT_TRUE(field.stored_rows() >= 10 && field.stored_rows() < 89)
      << "the edit below assumes a two-digit row count";
  bytes.replace(rows_key + 14, 2, "89");
  expect_refused(bytes, "clusters", "the header implies");
}

TEST(Container, WriteRefusesInconsistentFieldsAndLeavesNoFile) {
  TempDir dir;
  const auto path = dir / "bad.relume";
  auto expect_refused = [&](const CompressedField& field, const std::string& what,
                            const ContainerOptions& options = {}) {
    try {
      write_container(path, field, options);
      ADD_FAILURE() << "wrote a field with " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
  };
  CompressedField field = sample_field();
  field.cluster[2] = 3;
  expect_refused(field, "stored row 2 has cluster id 3");

  field = sample_field();
  std::size_t row = 0;
  while (field.residual.row_offsets[row + 1] - field.residual.row_offsets[row] < 2) ++row;
  std::swap(field.residual.values[field.residual.row_offsets[row]],
            field.residual.values[field.residual.row_offsets[row] + 1]);
  expect_refused(field, "not sorted by |value| descending");

  field = sample_field();
  field.residual.light_index[field.residual.row_offsets[row] + 1] =
      field.residual.light_index[field.residual.row_offsets[row]];
  expect_refused(field, "two residual entries at light");

  field = sample_field();
  std::swap(field.stored_function[0], field.stored_function[1]);
  expect_refused(field, "strictly ascending");

  field = sample_field();
  field.mask.pop_back();
  expect_refused(field, "the mask has 29 entries");

  field = sample_field();
  field.weights(0, 1) = INFINITY;
  expect_refused(field, "weight of stored row 0 term 1 is inf");

  ContainerOptions options;
  options.parameters_json = "[1, 2]";
  expect_refused(sample_field(), "must be a JSON object", options);
  options.parameters_json = "{oops";
  expect_refused(sample_field(), "not valid JSON", options);
}

TEST(Container, AFailedWriteLeavesTheOldFileInPlace) {
  TempDir dir;
  const auto path = dir / "a.relume";
  const CompressedField good = sample_field();
  write_container(path, good);
  CompressedField bad = good;
  bad.cluster[0] = 99;
  EXPECT_THROW(write_container(path, bad), Error);
  expect_identical(good, read_container(path));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename(), "a.relume");  // no temporary left behind
}

TEST(Container, VersionOneFilesStillRead) {
  for (const std::string name : {"v1_float32", "v1_float16"}) {
    const auto folder = testing::source_dir() / "tests/container/fixtures";
    ContainerOptions stored;
    const CompressedField field = read_container(folder / (name + ".relume"), &stored);
    EXPECT_EQ(describe_container(folder / (name + ".relume")).version, 1u);
    EXPECT_FALSE(stored.entropy_coding);
    EXPECT_EQ(stored.weights,
              name == "v1_float16" ? ValuePrecision::float16 : ValuePrecision::float32);
    EXPECT_EQ(nlohmann::json::parse(stored.parameters_json)["fixture"], "version 1");
    // What the version-1 reader reconstructed from it, bit for bit.
    const NpyMatrix expected = read_npy_matrix(folder / (name + "_reconstructed.npy"));
    const ReflectanceField reconstructed = reconstruct_field(field);
    ASSERT_EQ(expected.values.rows(), reconstructed.values.rows());
    ASSERT_EQ(expected.values.cols(), reconstructed.values.cols());
    for (Eigen::Index p = 0; p < expected.values.rows(); ++p)
      for (Eigen::Index i = 0; i < expected.values.cols(); ++i)
        ASSERT_EQ(float(expected.values(p, i)), reconstructed.values(p, i)) << name << " " << p;
    // Its content is sample_field()'s, which a version-2 file stores in fewer bytes.
    expect_identical(
        name == "v1_float16" ? quantize_for_container(sample_field(), stored) : sample_field(),
        field);
  }
}

// File `path`'s bytes with the format version set to `version` and the table's checksum redone.
std::string with_version(const std::filesystem::path& path, std::uint32_t version) {
  std::string bytes = read_file(path);
  const std::size_t table_end = describe_container(path).preamble_bytes;
  std::memcpy(bytes.data() + 8, &version, 4);  // little-endian, after the 8-byte magic
  const std::uint32_t crc = crc32(bytes.data(), table_end - 4);
  std::memcpy(bytes.data() + table_end - 4, &crc, 4);
  return bytes;
}

// Files that older relume writers made (tests/container/data): v3_* written from sample_field and
// testing::add_dark_pixels before version 4 added the dark gains, v4_* before version 5, v5_*
// before version 6.
std::filesystem::path version_three_file(const std::string& name) {
  return testing::source_dir() / "tests/container/data" / name;
}

TEST(Container, VersionThreeFilesStillRead) {
  const CompressedField field = sample_field();
  EXPECT_EQ(describe_container(version_three_file("v3_sample.relume")).version, 3u);
  expect_identical(field, read_container(version_three_file("v3_sample.relume")));

  // Dark pixels of version 3 have no gains: each relights as the dark model itself (gain 1).
  const CompressedField dark = read_container(version_three_file("v3_dark.relume"));
  ASSERT_FALSE(dark.dark_pixels.empty());
  EXPECT_TRUE(dark.dark_gains.empty());
  const ReflectanceField back = reconstruct_field(dark);
  const std::uint32_t q = dark.dark_pixels.back();
  for (int i = 0; i < dark.lights; ++i)
    EXPECT_EQ(back.values(q * dark.channels, i), dark.dark[std::size_t(i)]);
}

TEST(Container, VersionFourFilesStillRead) {
  // Written by relume before version 5 (tests/container/data: sample_field, and
  // sample_field_with_dark_pixels); version 5 added the weight_planes section.
  EXPECT_EQ(describe_container(version_three_file("v4_sample.relume")).version, 4u);
  const CompressedField sample = read_container(version_three_file("v4_sample.relume"));
  expect_identical(sample_field(), sample);
  EXPECT_TRUE(sample.coded_weights.empty());
  const CompressedField dark = read_container(version_three_file("v4_dark_gains.relume"));
  const CompressedField expected = sample_field_with_dark_pixels();
  expect_identical(expected, dark);
  EXPECT_EQ(dark.dark_pixels, expected.dark_pixels);
  EXPECT_EQ(dark.dark, expected.dark);
  EXPECT_EQ(dark.dark_gains, expected.dark_gains);
}

TEST(Container, VersionFiveFilesStillRead) {
  // Written by relume before version 6 added the weight_colour section (`relume synth -o s --size
  // 24x20 --lights 16`, `relume compress s -o v5_planes.relume --target-bytes 3000
  // --target-models one-basis`), with the W that relume read from it (`relume export`):
  // v5_planes_weights.npy. Its planes have one fixed colour transform for every term.
  const auto path = version_three_file("v5_planes.relume");
  EXPECT_EQ(describe_container(path).version, 5u);
  const CompressedField planes = read_container(path);
  EXPECT_FALSE(planes.coded_weights.empty());
  EXPECT_TRUE(planes.coded_weights.colour_angles.empty());
  const NpyMatrix expected = read_npy_matrix(version_three_file("v5_planes_weights.npy"));
  ASSERT_EQ(expected.values.rows(), planes.weights.rows());
  ASSERT_EQ(expected.values.cols(), planes.weights.cols());
  for (Eigen::Index r = 0; r < expected.values.rows(); ++r)
    for (Eigen::Index j = 0; j < expected.values.cols(); ++j)
      ASSERT_EQ(float(expected.values(r, j)), planes.weights(r, j)) << r << " " << j;
}

TEST(Container, VersionTwoFilesStillRead) {
  // Version 3 differs from version 2 only where a cluster leaves a basis row unused: then
  // version 2 stored its weights (zeros) and version 3 does not. A field that uses every row
  // has the same bytes in both, so the version-2 file is the version-3 file relabelled.
  TempDir dir;
  write_bytes(dir / "v2.relume", with_version(version_three_file("v3_sample.relume"), 2));
  EXPECT_EQ(describe_container(dir / "v2.relume").version, 2u);
  expect_identical(sample_field(), read_container(dir / "v2.relume"));

  // Where a row is unused, a version-2 reader expects every weight: the version-3 bytes are one
  // weight per stored row of cluster 0 short of that, and refused so.
  const auto unused = version_three_file("v3_unused_row.relume");
  write_bytes(dir / "unused_v2.relume", with_version(unused, 2));
  const std::string message = read_error(dir / "unused_v2.relume");
  EXPECT_NE(message.find("section 'weights'"), std::string::npos) << message;
}

TEST(Container, EntropyCodingIsLosslessAndSmallerOnCompressibleSections) {
  TempDir dir;
  RandomFieldShape shape;
  shape.width = 40;
  shape.height = 30;
  shape.lights = 64;
  shape.clusters = 4;
  shape.terms = 3;
  shape.residual_per_function = 6;
  CompressedField field = random_compressed_field(shape);
  // Neighbouring functions share clusters in real fields: runs that zstd codes well.
  for (std::size_t r = 0; r < field.stored_rows(); ++r) field.cluster[r] = std::uint32_t(r / 900);
  ContainerOptions raw;
  raw.entropy_coding = false;
  write_container(dir / "raw.relume", field, raw);
  write_container(dir / "coded.relume", field);
  ContainerOptions stored;
  expect_identical(field, read_container(dir / "coded.relume", &stored));
  EXPECT_TRUE(stored.entropy_coding);
  expect_identical(field, read_container(dir / "raw.relume"));
  const ContainerLayout coded = describe_container(dir / "coded.relume");
  const ContainerLayout plain = describe_container(dir / "raw.relume");
  EXPECT_EQ(plain.section("clusters").coding, "raw");
  EXPECT_EQ(coded.section("header").coding, "raw");  // the header stays readable
  EXPECT_NE(coded.section("clusters").coding, "raw");
  EXPECT_LT(coded.section("clusters").bytes, plain.section("clusters").bytes / 20);
  EXPECT_LT(coded.file_bytes, plain.file_bytes);
  for (const ContainerSection& section : coded.sections)
    EXPECT_EQ(section.raw_bytes, plain.section(section.name).raw_bytes) << section.name;
}

TEST(Container, ADamagedCodedSectionIsRefusedNamingTheSection) {
  TempDir dir;
  const auto path = dir / "a.relume";
  RandomFieldShape shape;
  shape.width = 20;
  shape.height = 10;
  shape.lights = 16;
  shape.clusters = 2;
  CompressedField field = random_compressed_field(shape);
  std::fill(field.cluster.begin(), field.cluster.end(), 1u);  // compressible
  write_container(path, field);
  const ContainerLayout layout = describe_container(path);
  const ContainerSection& clusters = layout.section("clusters");
  ASSERT_NE(clusters.coding, "raw");
  const std::string original = read_file(path);
  // The checksums fixed, so the damage reaches the decoder: zstd or its own checksum refuses it.
  for (std::size_t at :
       {clusters.offset + clusters.bytes / 2, clusters.offset + clusters.bytes - 1}) {
    std::string bytes = original;
    bytes[at] ^= 0x24;
    fix_checksums(bytes, layout);
    write_bytes(path, bytes);
    const std::string message = read_error(path);
    EXPECT_NE(message.find(path.string() + ": section 'clusters'"), std::string::npos) << message;
  }
  // A table that claims more decoded bytes than the coded bytes can hold is refused before
  // anything is allocated.
  std::string bytes = original;
  ByteWriter huge;
  huge.u64(std::uint64_t(1) << 40);
  std::size_t index = 0;
  while (layout.sections[index].name != "clusters") ++index;
  bytes.replace(table_start + entry_bytes * index + 32, 8, huge.data());
  fix_checksums(bytes, layout);
  write_bytes(path, bytes);
  const std::string message = read_error(path);
  EXPECT_NE(message.find("section 'clusters': "), std::string::npos) << message;
  EXPECT_NE(message.find("cannot decode to 1099511627776 bytes"), std::string::npos) << message;
}

TEST(SectionCoding, EveryFilterRoundTripsAndUnknownCodingsAreRefused) {
  std::string raw;
  for (int i = 0; i < 3000; ++i) raw.push_back(char((i / 7) * 3 % 251));
  for (int element : {1, 2, 4, 8}) {
    const std::string sized = raw.substr(0, raw.size() / element * element);
    const CodedSection coded = code_section(sized, element);
    EXPECT_LT(coded.bytes.size(), sized.size() / 4) << element;
    EXPECT_EQ(decode_section(coded.bytes, coded.coding, sized.size(), "s"), sized) << element;
    for (SectionFilter filter :
         {SectionFilter::none, SectionFilter::shuffle, SectionFilter::delta_shuffle}) {
      const SectionCoding coding{true, filter, element};
      EXPECT_EQ(SectionCoding::from_word(coding.word(), "s").describe(), coding.describe());
    }
  }
  // Random bytes do not compress: they stay raw.
  std::string noise;
  std::uint32_t state = 12345;
  for (int i = 0; i < 4096; ++i)
    noise.push_back(char((state = state * 1664525u + 1013904223u) >> 24));
  const CodedSection kept = code_section(noise, 1);
  EXPECT_FALSE(kept.coding.zstd);
  EXPECT_EQ(kept.bytes, noise);
  EXPECT_THAT(error_message([] { SectionCoding::from_word(0x00000307u, "f: section 'x'"); }),
              ::testing::HasSubstr("f: section 'x': unknown coding word 0x00000307"));
  const CodedSection coded = code_section(raw, 1);
  EXPECT_THAT(
      error_message([&] { decode_section(coded.bytes, coded.coding, raw.size() + 1, "w"); }),
      ::testing::HasSubstr("decompresses to 3000 bytes, the section table says 3001"));
}

TEST(Container, BadQuantizedStepsAndIntegersAreRefusedNamingTheSection) {
  TempDir dir;
  const CompressedField q = quantize_values(sample_field(), {0.002f, 0.004f, 10});
  ContainerOptions raw;
  raw.entropy_coding = false;
  const auto path = dir / "q.relume";
  write_container(path, q, raw);
  const std::string original = read_file(path);
  const ContainerLayout layout = describe_container(path);
  auto refused = [&](std::string bytes) {
    fix_checksums(bytes, layout);
    write_bytes(path, bytes);
    return read_error(path);
  };
  std::string bytes = original;
  const std::size_t step = bytes.find("\"weight_step\":", layout.section("header").offset);
  ASSERT_NE(step, std::string::npos);
  ASSERT_EQ(bytes.substr(step + 14, 2), "0.");
  bytes.replace(step + 14, 2, "-1");  // 0.002... becomes -1002...: a negative step
  EXPECT_THAT(refused(bytes), ::testing::HasSubstr("section 'header': 'weight_step'"));

  bytes = original;
  const ContainerSection& values = layout.section("residual_values");
  ASSERT_GE(values.bytes, 2u);
  bytes[values.offset] = 0;
  bytes[values.offset + 1] = char(0x80);  // -32768
  EXPECT_THAT(refused(bytes),
              ::testing::HasSubstr("section 'residual_values': holds the integer -32768"));

  bytes = original;
  const ContainerSection& scales = layout.section("basis_scales");
  for (int b = 0; b < 4; ++b) bytes[scales.offset + b] = 0;  // a scale of 0
  EXPECT_THAT(refused(bytes), ::testing::HasSubstr("section 'basis_scales': holds the scale 0"));
}

TEST(InfoCommand, PrintsDimensionsSectionsAndRatio) {
  TempDir dir;
  const auto path = dir / "a.relume";
  const CompressedField field = sample_field();
  ContainerOptions options;
  options.residual = ValuePrecision::float16;
  options.parameters_json = R"({"clusters": 3, "method": "lp-dual"})";
  write_container(path, field, options);
  const std::uint64_t file_bytes = std::filesystem::file_size(path);

  const auto text = testing::run_relume("info '" + path.string() + "'");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("6 x 5 pixels, 3 channels, 10 lights"), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("residual_values"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("lp-dual"), std::string::npos) << text.output;

  const auto json_run = testing::run_relume("info --json '" + path.string() + "'");
  ASSERT_EQ(json_run.exit_code, 0) << json_run.output;
  const nlohmann::json info = nlohmann::json::parse(json_run.output);
  EXPECT_EQ(info["width"], 6);
  EXPECT_EQ(info["height"], 5);
  EXPECT_EQ(info["channels"], 3);
  EXPECT_EQ(info["lights"], 10);
  EXPECT_EQ(info["clusters"], 3);
  EXPECT_EQ(info["terms"], 2);
  EXPECT_EQ(info["stored_rows"], field.stored_rows());
  EXPECT_EQ(info["residual_nonzeros"], field.residual.nonzeros());
  EXPECT_EQ(info["residual_precision"], "float16");
  EXPECT_EQ(info["light_index_bits"], 8);
  EXPECT_EQ(info["parameters"]["method"], "lp-dual");
  EXPECT_EQ(info["file_bytes"], file_bytes);
  const std::uint64_t input_bytes = 6 * 5 * 3 * 10 * 4;
  EXPECT_EQ(info["float32_input_bytes"], input_bytes);
  EXPECT_DOUBLE_EQ(info["ratio_to_float32_input"].get<double>(), double(file_bytes) / input_bytes);
  std::uint64_t section_total = 0;
  for (const auto& section : info["sections"])
    section_total += section["bytes"].get<std::uint64_t>();
  EXPECT_EQ(section_total + info["preamble_bytes"].get<std::uint64_t>(), file_bytes);
  EXPECT_EQ(info["sections"][15]["name"], "residual_values");
  EXPECT_EQ(info["sections"][15]["raw_bytes"], field.residual.nonzeros() * 2);
  EXPECT_LE(info["sections"][15]["bytes"], field.residual.nonzeros() * 2);
  EXPECT_DOUBLE_EQ(info["bits_per_stored_row"].get<double>(),
                   8.0 * double(file_bytes) / double(field.stored_rows()));

  write_bytes(dir / "junk.relume", "junk");
  const auto refused = testing::run_relume("info '" + (dir / "junk.relume").string() + "'");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("junk.relume is not a relume container"), std::string::npos)
      << refused.output;
}

}  // namespace
}  // namespace relume
