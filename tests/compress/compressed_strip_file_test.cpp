// The compressed field of a streamed compression kept on disk
// (lib/compress/compressed_strip_file.hpp) and stored from there (stored_strips,
// lib/compress/storage_precision.hpp): strips come back as appended, the shell holds everything but
// the stored rows, the file goes with the object, and the container written strip by strip from the
// file is the one the in-memory path writes for the same field (the same alignment, quantization
// steps and bytes).
#include "compress/compressed_strip_file.hpp"

#include <gtest/gtest.h>

#include <relume/container.hpp>

#include "compress/storage_precision.hpp"
#include "container/container.hpp"
#include "container/container_strips.hpp"
#include "core/atomic_file.hpp"
#include "field/field_strips.hpp"
#include "model/compressed_field_rows.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;
using testing::TempDir;

// 11 x 9 pixels, 1 channel, 20 lights, 4 clusters of 3 terms; every other pixel without stored
// rows is dark.
CompressedField sample_field() {
  RandomFieldShape shape;
  shape.width = 11;
  shape.height = 9;
  shape.channels = 1;
  shape.lights = 20;
  shape.clusters = 4;
  shape.terms = 3;
  shape.residual_per_function = 6;
  shape.vary_residual = true;
  shape.stored_fraction = 0.6;
  shape.seed = 11;
  CompressedField field = random_compressed_field(shape);
  testing::add_dark_pixels(field);
  return field;
}

// The bytes write_container writes for `field` (float32 unless quantized), to compare fields.
std::string container_bytes(const CompressedField& field) {
  return encode_container(field, {}, "test", nullptr);
}

// `field`'s strips of `rows` pixel rows appended to a file in `folder`, its bases given to the
// shell as the build pass gives them.
void fill(CompressedStripFile& file, const CompressedField& field, int rows) {
  for (int y = 0; y < field.height; y += rows)
    file.append(compressed_rows(field, y, std::min(rows, field.height - y)));
  file.shell().bases = field.bases;
}

TEST(CompressedStripFile, StripsComeBackAsAppendedAndTheFileGoes) {
  TempDir dir;
  const CompressedField field = sample_field();
  ASSERT_FALSE(field.dark_pixels.empty());
  fs::path path;
  {
    CompressedStripFile file(dir / "scratch", "out.relume.compressed");
    fill(file, field, 4);
    ASSERT_EQ(file.strips(), 3u);
    EXPECT_EQ(file.first_rows(), (std::vector<int>{0, 4, 8}));
    EXPECT_EQ(file.stored_rows(), field.stored_rows());
    for (std::size_t s = 0; s < 3; ++s) {
      const int y = int(s) * 4;
      EXPECT_EQ(container_bytes(file.read(s)),
                container_bytes(compressed_rows(field, y, std::min(4, field.height - y))))
          << "strip " << s;
    }
    // The shell is the field without its stored rows.
    const CompressedField& shell = file.shell();
    EXPECT_EQ(shell.height, field.height);
    EXPECT_EQ(shell.mask, field.mask);
    EXPECT_EQ(shell.dark_pixels, field.dark_pixels);
    EXPECT_EQ(shell.dark, field.dark);
    EXPECT_EQ(shell.stored_rows(), 0u);
    std::vector<std::size_t> sizes(4, 0);
    for (const std::uint32_t k : field.cluster) ++sizes[k];
    EXPECT_EQ(file.cluster_sizes(), sizes);
    EXPECT_THROW(file.read(3), std::out_of_range);
    path = dir / "scratch";
    EXPECT_FALSE(fs::is_empty(path));
  }
  EXPECT_TRUE(fs::is_empty(path)) << "the strip file is removed with its object";
}

// The in-memory path (store_with_precision_on_strips on the whole field) and the on-disk one
// (choose_strip_storage and stored_strips on its strips) choose the same steps against the same sample and write the same
// container, for float32, float16 and quantized storage.
TEST(StoredStrips, WriteTheContainerTheWholeFieldGives) {
  TempDir dir;
  const CompressedField field = sample_field();
  // An original the compressed field approximates.
  const ReflectanceField original = testing::noisy_original(field, 0.03);
  // Every third pixel row is the quantization's sample, as the build pass keeps it.
  ReflectanceField sample;
  std::vector<std::pair<int, int>> sample_rows;
  CompressedField sampled;
  for (int y = 1; y < field.height; y += 3) {
    append_field_rows(sample, original, y, 1);
    sample_rows.emplace_back(y, 1);
    append_compressed_rows(sampled, compressed_rows(field, y, 1));
  }
  CompressedStripFile file(dir / "scratch", "a.relume.compressed");
  fill(file, field, 2);
  StoragePrecision quantized;
  quantized.threads = 1;
  StoragePrecision half;
  half.weights = ValuePrecision::float16;
  half.residual = ValuePrecision::float16;
  half.quantize_bases = false;
  StoragePrecision float32 = half;
  float32.weights = float32.residual = ValuePrecision::float32;
  for (const StoragePrecision& precision : {quantized, half, float32}) {
    SCOPED_TRACE(to_string(precision.weights));
    CompressedField whole = field;
    const std::optional<QuantizationChoice> in_memory =
        store_with_precision_on_strips(sample, sample_rows, whole, precision);
    std::optional<QuantizationChoice> on_disk;
    const StripStorage storage = choose_strip_storage(sample, sampled, file, precision, on_disk);
    const CompressedFieldStrips stored = stored_strips(file, storage);
    ASSERT_EQ(in_memory.has_value(), on_disk.has_value());
    if (in_memory) {
      EXPECT_EQ(in_memory->steps.weight_step, on_disk->steps.weight_step);
      EXPECT_EQ(in_memory->steps.residual_step, on_disk->steps.residual_step);
      EXPECT_EQ(in_memory->steps.basis_bits, on_disk->steps.basis_bits);
      EXPECT_GT(on_disk->steps.weight_step, 0.0f);
    }
    const ContainerOptions options = precision.container_options();
    write_container(dir / "memory.relume", whole, options);
    write_container_strips(dir / "disk.relume", stored, options, dir / "scratch");
    EXPECT_TRUE(read_file(dir / "memory.relume") == read_file(dir / "disk.relume"));
  }
}

}  // namespace
}  // namespace relume
