// Tests of exporting compressed fields as NumPy .npz (lib/export/): the stored zip read back by
// Python's zipfile, the archive loaded by NumPy itself (no pickle) with the documented names,
// dtypes and shapes, and the field rebuilt in NumPy from W, F and the CSR residual equal to
// relume's own reconstruction; `relume export` on a real container and on bad input.
#include "export/npz_export.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <relume/error.hpp>

#include "core/atomic_file.hpp"
#include "export/stored_zip.hpp"
#include "field/npy.hpp"
#include "model/random_compressed_field.hpp"
#include "model/reconstruct_field.hpp"
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

TEST(NpzExport, NumpyLoadsTheArraysAndRebuildsTheField) {
  const std::string python = python_with_numpy();
  if (python.empty()) GTEST_SKIP() << "no python3 with numpy";
  testing::TempDir dir;
  RandomFieldShape shape;
  shape.width = 9, shape.height = 7, shape.lights = 23, shape.clusters = 5, shape.terms = 3;
  shape.residual_per_function = 6, shape.vary_residual = true, shape.stored_fraction = 0.7;
  const CompressedField field = random_compressed_field(shape);
  write_compressed_field_npz(dir / "field.npz", field);

  // NumPy rebuilds every function (zero where not stored) and saves it as float64.
  const auto result = run_python(
      python, dir,
      "import sys, numpy as np\n"
      "d = np.load(sys.argv[1])\n"
      "assert d['W'].dtype == np.float32 and d['W'].shape == (d['stored_function'].size, 3)\n"
      "assert d['F'].shape == (5, 3, 23) and d['mask'].shape == (7, 9)\n"
      "assert d['mask'].dtype == np.uint8 and d['cluster'].dtype == np.uint32\n"
      "assert int(d['width']) == 9 and int(d['lights']) == 23 and int(d['transform']) == 0\n"
      "assert 'CSR residual' in str(d['description'])\n"
      "rows = d['stored_function'].size\n"
      "R = np.zeros((int(d['height']) * int(d['width']) * int(d['channels']), 23))\n"
      "indptr, idx, val = d['residual_indptr'], d['residual_indices'], d['residual_data']\n"
      "for s in range(rows):\n"
      "    row = d['W'][s].astype(np.float64) @ d['F'][d['cluster'][s]].astype(np.float64)\n"
      "    row[idx[indptr[s]:indptr[s + 1]]] += val[indptr[s]:indptr[s + 1]]\n"
      "    R[d['stored_function'][s]] = row\n"
      "np.save(sys.argv[2], R)\n",
      quoted(dir / "field.npz") + " " + quoted(dir / "numpy.npy"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const NpyMatrix numpy = read_npy_matrix(dir / "numpy.npy");
  const ReflectanceField relume = reconstruct_field(field);
  ASSERT_EQ(numpy.values.rows(), relume.values.rows());
  ASSERT_EQ(numpy.values.cols(), relume.values.cols());
  EXPECT_LT((numpy.values - relume.values.cast<double>()).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_GT(relume.values.cwiseAbs().maxCoeff(), 0.1f);
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
