// Writes the binary seed inputs of the fuzz targets into fuzz/corpus/ (the text seeds are
// written by hand): small containers in every storage form the reader knows (raw and zstd-coded
// sections, float32, float16 and quantized values, 8-bit bases, dark pixels with gains), and
// .npy matrices. The version-3 seeds (v3_*.relume) were written by relume before version 4 and
// are kept by hand.
// Run by `scripts/fuzz.sh --make-seeds`; the seeds it wrote are committed.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

#include "container/container.hpp"
#include "core/atomic_file.hpp"
#include "field/npy.hpp"
#include "model/dark_gains.hpp"
#include "model/random_compressed_field.hpp"

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_container_seeds CORPUS_FOLDER\n");
    return 2;
  }
  const fs::path corpus = argv[1];
  relume::RandomFieldShape shape;
  shape.width = 5;
  shape.height = 4;
  shape.channels = 3;
  shape.lights = 9;
  shape.clusters = 3;
  shape.terms = 2;
  shape.residual_per_function = 3;
  shape.vary_residual = true;
  shape.stored_fraction = 0.7;
  relume::CompressedField field = relume::random_compressed_field(shape);
  for (std::size_t p = 0; p < field.mask.size(); ++p) field.mask[p] = p % 7 != 0;
  const fs::path containers = corpus / "container";
  fs::create_directories(containers);
  struct Form {
    const char* name;
    relume::ValuePrecision values;
    bool entropy_coding;
  };
  for (const Form& form : {Form{"raw_float32", relume::ValuePrecision::float32, false},
                           Form{"raw_float16", relume::ValuePrecision::float16, false},
                           Form{"zstd_float32", relume::ValuePrecision::float32, true}}) {
    relume::ContainerOptions options;
    options.weights = options.residual = form.values;
    options.entropy_coding = form.entropy_coding;
    relume::write_container(containers / (std::string(form.name) + ".relume"), field, options);
  }
  relume::CompressedField quantized = field;
  quantized.quantization.weight_step = 1.0f / 1024;
  quantized.quantization.residual_step = 1.0f / 2048;
  for (float& w : std::span(quantized.weights.data(), std::size_t(quantized.weights.size())))
    w = float(std::lround(w * 1024) / 1024.0);
  for (float& v : quantized.residual.values) v = float(std::lround(v * 2048) / 2048.0);
  for (bool entropy : {false, true}) {
    relume::ContainerOptions options;
    options.weights = options.residual = relume::ValuePrecision::quantized;
    options.entropy_coding = entropy;
    relume::write_container(
        containers / (entropy ? "zstd_quantized.relume" : "raw_quantized.relume"), quantized,
        options);
  }
  // Dark pixels with their block gains (version 4): the pixels inside the mask without stored
  // functions.
  relume::CompressedField dark = field;
  std::vector<std::uint8_t> stored(dark.mask.size(), 0);
  for (const std::uint32_t p : dark.stored_function) stored[p / std::uint32_t(dark.channels)] = 1;
  for (std::size_t q = 0; q < dark.mask.size(); ++q)
    if (dark.mask[q] && !stored[q]) dark.dark_pixels.push_back(std::uint32_t(q));
  dark.dark.assign(std::size_t(dark.channels) * dark.lights, 0.002f);
  dark.dark_gain_step = 0.25f;
  relume::DarkGainGrid grid = relume::empty_dark_gain_grid(dark.width, dark.height, dark.channels);
  for (std::size_t v = 0; v < grid.values.size(); ++v) grid.values[v] = std::int32_t(2 + v);
  relume::expand_dark_gains(dark, grid);
  relume::write_container(containers / "zstd_dark_gains.relume", dark);
  const fs::path npy = corpus / "npy";
  fs::create_directories(npy);
  Eigen::MatrixXd matrix(3, 4);
  for (Eigen::Index i = 0; i < matrix.size(); ++i) matrix.data()[i] = 0.25 * double(i) - 1;
  relume::write_npy_matrix(npy / "float64.npy", matrix, relume::NpyDtype::float64);
  relume::write_npy_matrix(npy / "float32.npy", matrix, relume::NpyDtype::float32);
  std::printf("wrote the binary seeds into %s\n", corpus.c_str());
  return 0;
}
