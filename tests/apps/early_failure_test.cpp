// Tests that the commands refuse bad options and unusable outputs before any long work (the
// input here does not exist, so any check that ran after loading would report that instead), name
// the output rather than its checkpoint, bound --threads and the sizes of synth, sky and factor,
// refuse work above --memory-limit with the numbers, and keep exit 2 for usage errors (non-finite
// numbers and targets of 0 among them).
#include <fstream>

#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::run_relume;

class EarlyFailure : public ::testing::Test {
 protected:
  std::string at(const std::string& name) const {
    std::string quoted = "'";
    return quoted.append((dir_ / name).string()).append("'");
  }
  testing::TempDir dir_;
};

TEST_F(EarlyFailure, CompressChecksOptionsAndOutputsBeforeLoading) {
  const std::string missing = at("missing-field");
  struct Case {
    std::string options, message;
  };
  std::filesystem::create_directories(dir_ / "existing");
  for (const Case& c :
       {Case{"--clusters 0", "clusters must be >= 1, got 0"},
        Case{"--terms 17", "terms per cluster must be in [1, 16]"},
        Case{"--weights-precision float8", "unknown precision \"float8\""},
        Case{"--bases-precision half", "--bases-precision must be 'quantized' or 'float32'"},
        Case{"--assign opencl --device no-such-device", "no-such-device"}}) {
    const auto run =
        run_relume("compress " + missing + " -o " + at("out.relume") + " " + c.options);
    EXPECT_EQ(run.exit_code, 1) << c.options;
    EXPECT_THAT(run.output, HasSubstr(c.message)) << c.options;
    EXPECT_THAT(run.output, Not(HasSubstr("not found"))) << c.options;
  }
  auto run = run_relume("compress " + missing + " -o " + at("existing") + " --assign cpu");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("existing: it is a folder"));
  EXPECT_THAT(run.output, Not(HasSubstr("checkpoint")));
  run = run_relume("compress " + missing + " -o " + at("no/such/folder/out.relume") +
                   " --assign cpu");
  EXPECT_THAT(run.output,
              HasSubstr("folder " + (dir_ / "no/such/folder").string() + " does not exist"));
  EXPECT_THAT(run.output, Not(HasSubstr("checkpoint")));
}

// `-o plainfile/x.relume` said that the folder did not exist; `-o /proc/x.relume` failed only
// after loading, naming the checkpoint.
TEST_F(EarlyFailure, CompressNamesAFileForAFolderAndAFolderThatTakesNoFiles) {
  std::ofstream(dir_ / "plainfile") << "a file";
  auto run = run_relume("compress " + at("missing-field") + " -o " + at("plainfile/x.relume") +
                        " --assign cpu");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr((dir_ / "plainfile").string() + " is a file, not a folder"));
  EXPECT_THAT(run.output, Not(HasSubstr("does not exist")));
  run = run_relume("compress " + at("missing-field") + " -o /proc/x.relume --assign cpu");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("cannot write /proc/x.relume: folder /proc is not writable"));
  EXPECT_THAT(run.output, Not(HasSubstr("not found")));
  EXPECT_THAT(run.output, Not(HasSubstr("checkpoint")));
}

// inf, nan and overflowing values were taken by CLI11 like numbers (`sky --sun-elevation inf`
// wrote a map without a sun), and a target of 0 was taken as no target.
TEST_F(EarlyFailure, NonFiniteNumbersAndTargetsOfZeroAreUsageErrorsNamingTheOption) {
  struct Case {
    std::string arguments, message;
  };
  const std::string compress = "compress " + at("missing-field") + " -o " + at("out.relume");
  for (const Case& c :
       {Case{"sky -o " + at("sky.exr") + " --sun-elevation inf",
             "--sun-elevation: must be a finite number, got 'inf'"},
        Case{"sky -o " + at("sky.exr") + " --sun-elevation -NaN",
             "--sun-elevation: must be a finite number, got '-NaN'"},
        Case{compress + " --light-weighting 1e999",
             "--light-weighting: must be a finite number, got '1e999'"},
        Case{compress + " --noise-floor nan", "--noise-floor: must be a finite number, got 'nan'"},
        Case{"relight " + at("missing.relume") + " --light-dir 0,inf,1 -o " + at("x.png"),
             "--light-dir: must be a finite number, got 'inf'"},
        Case{compress + " --target-bytes-per-pixel 0",
             "--target-bytes-per-pixel: must be > 0, got '0'"},
        Case{compress + " --target-bytes 0", "--target-bytes: must be > 0, got '0'"},
        Case{compress + " --target-psnr -3", "--target-psnr: must be > 0, got '-3'"},
        Case{compress + " --target-error 0", "--target-error: must be > 0, got '0'"}}) {
    const auto run = run_relume(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.output;
    EXPECT_THAT(run.output, HasSubstr(c.message)) << c.arguments;
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ / "sky.exr"));
}

TEST_F(EarlyFailure, RelightChecksTheDeviceAndOutputBeforeReading) {
  auto run = run_relume("relight " + at("missing.relume") + " --lights x.txt -o " + at("out.exr") +
                        " --device no-such-device");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("no-such-device"));
  std::ofstream(dir_ / "no") << "a file";
  run = run_relume("relight-sequence " + at("missing.relume") + " --env sky.exr -o " +
                   at("no/frames/%03d.png") + " --cpu");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("is not a folder"));
}

TEST_F(EarlyFailure, SizesAndThreadsHaveSaneBounds) {
  auto run = run_relume("synth -o " + at("s") + " --samples 100000");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("samples per pixel axis must be from 1 to 64"));
  run = run_relume("synth -o " + at("s") + " --lights 2000000000");
  EXPECT_THAT(run.output, HasSubstr("light count must be from 1 to 65536"));
  run = run_relume("synth -o " + at("s") + " --size 100000x100000");
  EXPECT_THAT(run.output, HasSubstr("image size must be from 1x1 to 16384x16384"));
  run = run_relume("sky -o " + at("sky.exr") + " --width 2000000");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("sky width must be an even number from 4 to 32768"));
  run = run_relume("synth -o " + at("s") + " --threads 100000");
  EXPECT_EQ(run.exit_code, 2);  // a usage error, refused while parsing
  EXPECT_THAT(run.output, HasSubstr("--threads"));
}

TEST_F(EarlyFailure, FactorRefusesMoreTermsThanTheMatrixHas) {
  // A 3 x 4 float64 .npy matrix.
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }";
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string bytes = std::string("\x93NUMPY\x01\x00", 8) + char(header.size()) + '\0' + header;
  for (int i = 0; i < 12; ++i) {
    const double v = i + 1;
    bytes.append(reinterpret_cast<const char*>(&v), 8);
  }
  std::ofstream(dir_ / "m.npy", std::ios::binary) << bytes;
  const auto run = run_relume("factor " + at("m.npy") + " -t 2000000000 -o " + at("f"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("2000000000 terms for a 3 x 4 matrix, expected at most "
                                    "min(rows, columns) = 3"));
}

TEST_F(EarlyFailure, WorkAboveTheMemoryLimitIsRefusedWithTheNumbers) {
  // synth writes a row at a time: two rows (48 KB each) and the mask (256 KB) must fit.
  auto run = run_relume("--memory-limit 100K synth -o " + at("s") + " --size 512x512 --lights 8");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("a synthetic field of 512x512 pixels and 8 lights, written a "
                                    "row at a time, needs about 352.0 KB, more than the 100.0 KB "
                                    "available (--memory-limit)"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "s"));
  run = run_relume("--memory-limit lots synth -o " + at("s"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("'lots' is not a size in bytes"));
}

TEST_F(EarlyFailure, FilesystemErrorsNameThePathWithExitOne) {
  // A name longer than any file system allows: std::filesystem throws, the command says so.
  const std::string long_name(5000, 'a');
  const auto run = run_relume("info " + at(long_name + ".relume"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.output, HasSubstr("relume: error: File name too long: "));
  EXPECT_THAT(run.output, HasSubstr(long_name));
  EXPECT_THAT(run.output, Not(HasSubstr("internal error")));
}

TEST_F(EarlyFailure, HostileLightFilesAreErrorsNotInternalErrors) {
  std::ofstream(dir_ / "huge.lp") << "9223372036854775808\na.png 0 0 1\n";
  std::ofstream(dir_ / "tabs.lp") << "1\n\v\n";
  for (const char* name : {"huge.lp", "tabs.lp"}) {
    const auto run =
        run_relume(std::string("compress ") + at(name) + " -o " + at("o.relume") + " --assign cpu");
    EXPECT_EQ(run.exit_code, 1) << name;
    EXPECT_THAT(run.output, HasSubstr("relume: error: ")) << name;
    EXPECT_THAT(run.output, Not(HasSubstr("internal error"))) << name;
  }
}

}  // namespace
}  // namespace relume
