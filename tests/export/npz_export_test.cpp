// Tests of exporting compressed fields as NumPy .npz (lib/export/): the stored zip read back by
// Python's zipfile, the archive loaded by NumPy itself (no pickle) with every array named in its
// description and of the described dtype and shape, the images `relume decompress` writes
// rebuilt from the archive alone by NumPy (rebuild_from_npz.py: quantized values, Haar, dark
// pixels, a mask, intensities, one and three channels); `relume export` on a real container and
// on bad input.
#include "export/npz_export.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <relume/container.hpp>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "core/atomic_file.hpp"
#include "export/stored_zip.hpp"
#include "field/npy.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;

// A python3 that can import numpy, or "" when there is none.
std::string python_with_numpy() {
  for (const char* python : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(python) + " -c 'import numpy' >/dev/null 2>&1").c_str()) == 0)
      return python;
  return "";
}

// 'path', for a shell command line.
std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

// Runs a Python script file with arguments; returns its output and exit status.
testing::CommandResult run_python(const std::string& python, const testing::TempDir& dir,
                                  const std::string& script, const std::string& arguments) {
  write_file_atomically(dir / "script.py", script);
  return testing::run_command(python + " " + quoted(dir / "script.py") + " " + arguments);
}

TEST(StoredZip, PythonsZipfileReadsTheEntriesBack) {
  const std::string python = python_with_numpy();
  if (python.empty()) GTEST_SKIP() << "no python3 (with numpy) to read the archive";
  testing::TempDir dir;
  std::string binary(300, '\0');
  for (std::size_t i = 0; i < binary.size(); ++i) binary[i] = static_cast<char>(i * 7);
  write_file_atomically(dir / "a.zip", stored_zip({{"first.txt", "hello"}, {"b/second", binary}}));
  const auto result = run_python(python, dir,
                                 "import sys, zipfile\n"
                                 "z = zipfile.ZipFile(sys.argv[1])\n"
                                 "assert z.testzip() is None\n"
                                 "assert z.namelist() == ['first.txt', 'b/second']\n"
                                 "assert z.read('first.txt') == b'hello'\n"
                                 "assert z.read('b/second') == bytes((i * 7) % 256 for i in "
                                 "range(300))\n"
                                 "assert all(i.compress_type == zipfile.ZIP_STORED for i in "
                                 "z.infolist())\n"
                                 "print('ok')\n",
                                 quoted(dir / "a.zip"));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, HasSubstr("ok"));
  EXPECT_THAT(testing::error_message([] {
                stored_zip({{"x", "1"}, {"x", "2"}});
              }),
              HasSubstr("given twice"));
}

TEST(NpzExport, NumpyLoadsEveryArrayWithTheDescribedTypeAndShape) {
  const std::string python = python_with_numpy();
  if (python.empty()) GTEST_SKIP() << "no python3 with numpy";
  testing::TempDir dir;
  RandomFieldShape shape;
  shape.width = 9, shape.height = 7, shape.lights = 23, shape.clusters = 5, shape.terms = 3;
  shape.residual_per_function = 6, shape.vary_residual = true, shape.stored_fraction = 0.7;
  const CompressedField field = random_compressed_field(shape);
  write_compressed_field_npz(dir / "field.npz", field);

  const auto result = run_python(
      python, dir,
      "import sys, numpy as np\n"
      "d = np.load(sys.argv[1])\n"
      "rows = d['stored_function'].size\n"
      "expected = {'width': ('i8', ()), 'height': ('i8', ()), 'channels': ('i8', ()),\n"
      "  'lights': ('i8', ()), 'terms': ('i8', ()), 'clusters': ('i8', ()),\n"
      "  'transform': ('i8', ()), 'mask': ('u1', (7, 9)), 'directions': ('f4', (23, 3)),\n"
      "  'intensities': ('f4', (23, 3)), 'stored_function': ('u4', (rows,)),\n"
      "  'cluster': ('u4', (rows,)), 'W': ('f4', (rows, 3)), 'F': ('f4', (5, 3, 23)),\n"
      "  'residual_indptr': ('u4', (rows + 1,)),\n"
      "  'residual_indices': ('u4', (d['residual_data'].size,)),\n"
      "  'residual_data': ('f4', (int(d['residual_indptr'][-1]),)),\n"
      "  'dark_pixels': ('u4', (0,)), 'dark': ('f4', (0, 23)),\n"
      "  'dark_gains': ('f4', (0, 3)), 'non_negative': ('b1', ()),\n"
      "  'weight_step': ('f4', ()), 'residual_step': ('f4', ()), 'basis_bits': ('i8', ()),\n"
      "  'basis_scales': ('f4', (0, 3)), 'description': ('U', ())}\n"
      "assert sorted(d.files) == sorted(expected), d.files\n"
      "for name, (dtype, shape) in expected.items():\n"
      "    assert d[name].dtype.str.lstrip('<|').startswith(dtype), (name, d[name].dtype)\n"
      "    assert d[name].shape == shape, (name, d[name].shape)\n"
      "description = str(d['description'])\n"
      "for name in expected:\n"
      "    assert name == 'description' or name in description, name\n"
      "assert int(d['width']) == 9 and int(d['transform']) == 0 and not d['non_negative']\n",
      quoted(dir / "field.npz"));
  EXPECT_EQ(result.exit_code, 0) << result.output;
}

// A field with every part the archive carries: quantized values, the Haar basis (over an odd
// light count), dark pixels with their gains, pixels outside the mask and intensities other than
// one.
CompressedField field_with_every_part(int channels, BasisTransform transform) {
  RandomFieldShape shape;
  shape.width = 9, shape.height = 7, shape.channels = channels, shape.lights = 23;
  shape.clusters = 4, shape.terms = 3, shape.residual_per_function = 5;
  shape.vary_residual = true, shape.stored_fraction = 0.5, shape.seed = 5;
  CompressedField field =
      quantize_values(random_compressed_field(shape), {1.0f / 4096, 1.0f / 8192, 12});
  field.transform = transform;
  testing::add_dark_pixels(field);
  testing::add_dark_gains(field);
  for (int i = 0; i < field.lights; ++i)
    for (int c = 0; c < 3; ++c) field.intensities(i, c) = 0.5f + 0.125f * float((3 * i + c) % 13);
  field.non_negative = true;
  return field;
}

TEST(NpzExport, NumpyAloneRebuildsTheImagesDecompressWrites) {
  const std::string python = python_with_numpy();
  if (python.empty()) GTEST_SKIP() << "no python3 with numpy";
  for (const auto& [channels, transform] :
       {std::pair{3, BasisTransform::haar}, std::pair{1, BasisTransform::identity}}) {
    SCOPED_TRACE(std::to_string(channels) + " channels");
    testing::TempDir dir;
    const CompressedField field = field_with_every_part(channels, transform);
    ASSERT_FALSE(field.dark_pixels.empty());
    ASSERT_NE(std::count(field.mask.begin(), field.mask.end(), 0), 0);
    write_container(dir / "field.relume", field);
    const std::string container = quoted(dir / "field.relume");
    const auto exported =
        testing::run_relume("export " + container + " --to npz " + quoted(dir / "field.npz"));
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    const auto decompressed =
        testing::run_relume("decompress " + container + " -o " + quoted(dir / "images"));
    ASSERT_EQ(decompressed.exit_code, 0) << decompressed.output;
    const auto rebuilt = testing::run_command(
        python + " " + quoted(testing::source_dir() / "tests/export/rebuild_from_npz.py") + " " +
        quoted(dir / "field.npz") + " " + quoted(dir / "rebuilt.npy"));
    ASSERT_EQ(rebuilt.exit_code, 0) << rebuilt.output;

    const Eigen::MatrixXd numpy = read_npy_matrix(dir / "rebuilt.npy").values;
    ASSERT_EQ(numpy.rows(), field.lights);
    ASSERT_EQ(numpy.cols(), field.functions());
    std::ifstream names(dir / "images" / "filenames.txt");
    std::string name;
    double largest = 0;
    for (int i = 0; i < field.lights && std::getline(names, name); ++i) {
      const Image image = read_image(dir / "images" / name);
      ASSERT_EQ(std::int64_t(image.pixels.size()), field.functions());
      for (std::size_t v = 0; v < image.pixels.size(); ++v) {
        const double expected = numpy(i, Eigen::Index(v));
        ASSERT_NEAR(image.pixels[v], expected, 1e-5 * std::max(1.0, std::abs(expected)))
            << "light " << i << ", value " << v;
        largest = std::max(largest, std::abs(expected));
      }
    }
    EXPECT_GT(largest, 0.1);
    // The dark model is what lights the dark pixels: some light shows them.
    const std::size_t dark = std::size_t(field.dark_pixels.front()) * field.channels;
    EXPECT_GT(numpy.col(Eigen::Index(dark)).cwiseAbs().maxCoeff(), 1e-4);
  }
}

TEST(ExportCommand, ExportsAContainerAndRefusesBadInput) {
  const std::string python = python_with_numpy();
  testing::TempDir dir;
  auto run = [&](const std::string& arguments) { return testing::run_relume(arguments); };
  ASSERT_EQ(run("synth -o '" + (dir / "scene").string() + "' --size 12x10 --lights 16 --samples 1")
                .exit_code,
            0);
  ASSERT_EQ(run("compress '" + (dir / "scene").string() + "' -o '" +
                (dir / "scene.relume").string() + "' --clusters 2 --terms 2 --residual 3")
                .exit_code,
            0);
  const std::string out = (dir / "scene.npz").string();
  const auto exported =
      run("export '" + (dir / "scene.relume").string() + "' --to npz '" + out + "'");
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_THAT(exported.output, HasSubstr("wrote " + out));
  if (!python.empty()) {
    const auto loaded =
        testing::run_command(python + " -c \"import numpy as np; d = np.load('" + out +
                             "'); print(sorted(d.files)); print(d['directions'].shape)\"");
    EXPECT_EQ(loaded.exit_code, 0) << loaded.output;
    EXPECT_THAT(loaded.output, HasSubstr("'residual_indptr'"));
    EXPECT_THAT(loaded.output, HasSubstr("(16, 3)"));
  }
  const auto again = run("export '" + (dir / "scene.relume").string() + "' --to npz '" + out + "'");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_THAT(again.output, HasSubstr("exists"));
  const auto format = run("export '" + (dir / "scene.relume").string() + "' --to hdf5 '" +
                          (dir / "x.h5").string() + "'");
  EXPECT_EQ(format.exit_code, 2) << format.output;
  const auto missing = run("export '" + (dir / "none.relume").string() + "' --to npz '" +
                           (dir / "none.npz").string() + "'");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.output, HasSubstr("none.relume"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none.npz"));
}

}  // namespace
}  // namespace relume
