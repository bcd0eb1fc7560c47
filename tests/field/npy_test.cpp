// Tests of the .npy reader and writer: files written by NumPy 1.24 (embedded below as hex, so the
// test needs no Python) in every supported layout, byte-identical output, clear errors for
// malformed files, and a live round trip through NumPy when a python3 with numpy is installed.
#include "field/npy.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <relume/error.hpp>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

std::string from_hex(const std::string& hex) {
  std::string bytes;
  for (std::size_t k = 0; k + 1 < hex.size(); k += 2)
    bytes += static_cast<char>(std::stoi(hex.substr(k, 2), nullptr, 16));
  return bytes;
}

// np.save of np.array([[1.5, -2.0, 3.25], [0.0, 1e-8, -7e5]]) in several layouts.
const std::string kFloat64 = from_hex(
    "934e554d5059010076007b276465736372273a20273c6638272c2027666f727472616e5f6f726465"
    "72273a2046616c73652c20277368617065273a2028322c2033292c207d2020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a000000000000f83f00000000000000c00000000000000a400000000000000000"
    "3a8c30e28e79453e00000000c05c25c1");
const std::string kFloat32 = from_hex(
    "934e554d5059010076007b276465736372273a20273c6634272c2027666f727472616e5f6f726465"
    "72273a2046616c73652c20277368617065273a2028322c2033292c207d2020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a0000c03f000000c0000050400000000077cc2b3200e62ac9");
const std::string kFortranOrder = from_hex(
    "934e554d5059010076007b276465736372273a20273c6638272c2027666f727472616e5f6f726465"
    "72273a20547275652c20277368617065273a2028322c2033292c207d202020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a000000000000f83f000000000000000000000000000000c03a8c30e28e79453e"
    "0000000000000a4000000000c05c25c1");
const std::string kBigEndian = from_hex(
    "934e554d5059010076007b276465736372273a20273e6638272c2027666f727472616e5f6f726465"
    "72273a2046616c73652c20277368617065273a2028322c2033292c207d2020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a3ff8000000000000c000000000000000400a0000000000000000000000000000"
    "3e45798ee2308c3ac1255cc000000000");
const std::string kVersion2 = from_hex(
    "934e554d50590200740000007b276465736372273a20273c6638272c2027666f727472616e5f6f72"
    "646572273a2046616c73652c20277368617065273a2028322c2033292c207d202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a000000000000f83f00000000000000c00000000000000a400000000000000000"
    "3a8c30e28e79453e00000000c05c25c1");
// np.arange(6).reshape(2, 3) (int64) and np.arange(3.0) (1-D).
const std::string kInt64 = from_hex(
    "934e554d5059010076007b276465736372273a20273c6938272c2027666f727472616e5f6f726465"
    "72273a2046616c73652c20277368617065273a2028322c2033292c207d2020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a0000000000000000010000000000000002000000000000000300000000000000"
    "04000000000000000500000000000000");
const std::string kOneDimensional = from_hex(
    "934e554d5059010076007b276465736372273a20273c6638272c2027666f727472616e5f6f726465"
    "72273a2046616c73652c20277368617065273a2028332c292c207d20202020202020202020202020"
    "20202020202020202020202020202020202020202020202020202020202020202020202020202020"
    "202020202020200a0000000000000000000000000000f03f0000000000000040");

Eigen::MatrixXd expected_matrix() {
  Eigen::MatrixXd m(2, 3);
  m << 1.5, -2.0, 3.25, 0.0, 1e-8, -7e5;
  return m;
}

std::string error_of(const std::string& bytes) {
  return testing::error_message([&] { parse_npy_matrix(bytes, "input.npy"); });
}

TEST(Npy, ReadsEveryLayoutNumpyWrites) {
  for (const std::string* bytes : {&kFloat64, &kFortranOrder, &kBigEndian, &kVersion2}) {
    const NpyMatrix matrix = parse_npy_matrix(*bytes, "x.npy");
    EXPECT_EQ(matrix.dtype, NpyDtype::float64);
    EXPECT_EQ(matrix.values, expected_matrix());
  }
  const NpyMatrix single = parse_npy_matrix(kFloat32, "x.npy");
  EXPECT_EQ(single.dtype, NpyDtype::float32);
  EXPECT_EQ(single.values, expected_matrix().cast<float>().cast<double>());
}

TEST(Npy, WritesTheSameBytesAsNumpy) {
  EXPECT_EQ(encode_npy_matrix(expected_matrix(), NpyDtype::float64), kFloat64);
  EXPECT_EQ(encode_npy_matrix(expected_matrix(), NpyDtype::float32), kFloat32);
}

TEST(Npy, RoundTripsThroughAFile) {
  testing::TempDir dir;
  const Eigen::MatrixXd values = Eigen::MatrixXd::Random(37, 5) * 1e3;
  write_npy_matrix(dir / "m.npy", values, NpyDtype::float64);
  EXPECT_EQ(read_npy_matrix(dir / "m.npy").values, values);
  write_npy_matrix(dir / "empty.npy", Eigen::MatrixXd(0, 4), NpyDtype::float32);
  const NpyMatrix empty = read_npy_matrix(dir / "empty.npy");
  EXPECT_EQ(empty.values.rows(), 0);
  EXPECT_EQ(empty.values.cols(), 4);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2)
      << "temporary files left behind";
}

TEST(Npy, RefusesMalformedFilesWithAClearMessage) {
  EXPECT_NE(error_of("hello world").find("not a .npy file"), std::string::npos);
  EXPECT_NE(error_of(kFloat64.substr(0, 9)).find("truncated"), std::string::npos);
  EXPECT_NE(error_of(kFloat64.substr(0, 60)).find("truncated"), std::string::npos);
  const std::string short_data = error_of(kFloat64.substr(0, kFloat64.size() - 8));
  EXPECT_NE(short_data.find("truncated .npy data"), std::string::npos) << short_data;
  EXPECT_NE(short_data.find("(2, 3)"), std::string::npos) << short_data;
  EXPECT_NE(error_of(kFloat64 + "xx").find("oversized"), std::string::npos);
  const std::string integer = error_of(kInt64);
  EXPECT_NE(integer.find("'<i8'"), std::string::npos) << integer;
  EXPECT_NE(integer.find("astype"), std::string::npos) << integer;
  const std::string one_d = error_of(kOneDimensional);
  EXPECT_NE(one_d.find("2-D"), std::string::npos) << one_d;
  EXPECT_NE(one_d.find("(3,)"), std::string::npos) << one_d;
  std::string version9 = kFloat64;
  version9[6] = 9;
  EXPECT_NE(error_of(version9).find("version 9.0"), std::string::npos);
  std::string garbled = kFloat64;
  garbled.replace(garbled.find("'shape'"), 7, "'shope'");
  EXPECT_NE(error_of(garbled).find("no 'shape' entry"), std::string::npos);
  std::string bad_syntax = kFloat64;
  bad_syntax.replace(bad_syntax.find("(2, 3)"), 6, "[2, 3]");
  EXPECT_NE(error_of(bad_syntax).find("malformed .npy header"), std::string::npos);
  EXPECT_THROW(read_npy_matrix("/nonexistent/relume.npy"), Error);
}

TEST(Npy, RefusesValuesThatDoNotFitFloat32) {
  Eigen::MatrixXd values = Eigen::MatrixXd::Ones(2, 2);
  values(1, 0) = 1e300;
  EXPECT_THROW(encode_npy_matrix(values, NpyDtype::float32), Error);
  EXPECT_NO_THROW(encode_npy_matrix(values, NpyDtype::float64));
}

// A python3 that can import numpy, or "" when there is none.
std::string python_with_numpy() {
  for (const char* python : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(python) + " -c 'import numpy' >/dev/null 2>&1").c_str()) == 0)
      return python;
  return "";
}

TEST(Npy, RoundTripsThroughNumpyItself) {
  const std::string python = python_with_numpy();
  if (python.empty())
    GTEST_SKIP() << "no python3 with numpy (the embedded NumPy files above still ran)";
  testing::TempDir dir;
  const Eigen::MatrixXd values = Eigen::MatrixXd::Random(6, 4);
  write_npy_matrix(dir / "relume.npy", values, NpyDtype::float32);
  const std::string script =
      "import numpy as np, sys; d = sys.argv[1]; a = np.load(d + '/relume.npy'); "
      "assert a.dtype == np.float32 and a.shape == (6, 4); "
      "np.save(d + '/numpy.npy', (a.astype(np.float64) * 2).T.copy(order='F'))";
  ASSERT_EQ(std::system((python + " -c \"" + script + "\" " + dir.path().string()).c_str()), 0);
  const NpyMatrix back = read_npy_matrix(dir / "numpy.npy");
  EXPECT_EQ(back.values, (values.cast<float>().cast<double>() * 2).transpose());
}

}  // namespace
}  // namespace relume
