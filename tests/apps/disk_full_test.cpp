// Disk-full tests of the commands that write much: compress, decompress, relight-sequence and
// synth write onto a 96 KB tmpfs (mounted by the test, which runs as root; where mounting is not
// allowed, a 96 KB file-size limit stands in). Each must fail with exit 1 and a message saying
// why, and leave nothing half-written: no temporary files, no partial output folder, every frame
// that exists complete.
#include <sys/mount.h>

#include <fstream>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;
using ::testing::AnyOf;
using ::testing::HasSubstr;
using testing::run_relume;

// A small full-able place to write: a tmpfs of 96 KB, or a shell prefix that limits file sizes.
class SmallDisk {
 public:
  explicit SmallDisk(const fs::path& folder) : folder_(folder) {
    fs::create_directories(folder);
    mounted_ = ::mount("tmpfs", folder.c_str(), "tmpfs", 0, "size=96k") == 0;
  }
  ~SmallDisk() {
    if (mounted_) ::umount(folder_.c_str());
  }
  // The shell prefix of a command that writes there.
  std::string prefix() const { return mounted_ ? "" : "ulimit -f 96; trap '' XFSZ; "; }
  const fs::path& folder() const { return folder_; }
  std::string how() const { return mounted_ ? "96 KB tmpfs" : "96 KB file-size limit"; }

 private:
  fs::path folder_;
  bool mounted_ = false;
};

testing::CommandResult relume_on(const SmallDisk& disk, const std::string& arguments) {
  return testing::run_command(disk.prefix() + "'" + std::string(RELUME_BINARY) + "' -q " +
                              arguments);
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().starts_with(".tmp-"))
      names.push_back(entry.path().string());
  return names;
}

const auto out_of_space = AnyOf(HasSubstr("No space left on device"), HasSubstr("File too large"),
                                HasSubstr("cannot write"));

class DiskFull : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new testing::TempDir;
    const std::string scene = (*data_ / "scene").string();
    ASSERT_EQ(
        run_relume("-q synth -o '" + scene + "' --size 48x40 --lights 12 --samples 1").exit_code,
        0);
    const auto run =
        run_relume("-q compress '" + scene + "' -o '" + (*data_ / "scene.relume").string() +
                   "' --clusters 4 --terms 2 --assign cpu --weights-precision "
                   "float32 --residual-precision float32 --bases-precision float32");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite() { delete data_; }

  testing::TempDir dir_;
  SmallDisk disk_{dir_ / "disk"};
  static testing::TempDir* data_;
};

testing::TempDir* DiskFull::data_ = nullptr;

TEST_F(DiskFull, Synth) {
  const auto run = relume_on(disk_, "synth -o '" + (disk_.folder() / "scene").string() +
                                        "' --size 64x64 --lights 12 --samples 1");
  EXPECT_EQ(run.exit_code, 1) << disk_.how() << ": " << run.output;
  EXPECT_THAT(run.output, out_of_space);
  EXPECT_FALSE(fs::exists(disk_.folder() / "scene")) << "a partial field folder is exposed";
  EXPECT_THAT(temporaries(disk_.folder()), ::testing::IsEmpty());
}

TEST_F(DiskFull, Decompress) {
  const auto run = relume_on(disk_, "decompress '" + (*data_ / "scene.relume").string() + "' -o '" +
                                        (disk_.folder() / "field").string() + "'");
  EXPECT_EQ(run.exit_code, 1) << disk_.how() << ": " << run.output;
  EXPECT_THAT(run.output, out_of_space);
  EXPECT_FALSE(fs::exists(disk_.folder() / "field")) << "a partial field folder is exposed";
  EXPECT_THAT(temporaries(disk_.folder()), ::testing::IsEmpty());
}

TEST_F(DiskFull, Compress) {
  // A bigger field than the disk holds as a float32 container.
  const std::string scene = (dir_ / "big").string();
  ASSERT_EQ(
      run_relume("-q synth -o '" + scene + "' --size 96x96 --lights 24 --samples 1").exit_code, 0);
  const auto run = relume_on(
      disk_, "compress '" + scene + "' -o '" + (disk_.folder() / "big.relume").string() +
                 "' --clusters 4 --terms 2 --residual 8 --assign cpu --weights-precision float32 "
                 "--residual-precision float32 --bases-precision float32");
  EXPECT_EQ(run.exit_code, 1) << disk_.how() << ": " << run.output;
  EXPECT_THAT(run.output, out_of_space);
  EXPECT_THAT(run.output, HasSubstr("big.relume"));
  EXPECT_FALSE(fs::exists(disk_.folder() / "big.relume"));
  EXPECT_THAT(temporaries(disk_.folder()), ::testing::IsEmpty());
}

TEST_F(DiskFull, RelightSequence) {
  const std::string sky = (dir_ / "sky.exr").string();
  ASSERT_EQ(run_relume("-q sky -o '" + sky + "' --width 64").exit_code, 0);
  const auto frames =
      relume_on(disk_, "relight-sequence '" + (*data_ / "scene.relume").string() + "' --env '" +
                           sky + "' --frames 40 -o '" +
                           (disk_.folder() / "frames" / "%03d.exr").string() + "' --cpu");
  EXPECT_EQ(frames.exit_code, 1) << disk_.how() << ": " << frames.output;
  EXPECT_THAT(frames.output, out_of_space);
  EXPECT_THAT(temporaries(disk_.folder()), ::testing::IsEmpty());
  // The frames that were written are whole images of the field's size.
  int complete = 0;
  for (const auto& entry : fs::directory_iterator(disk_.folder() / "frames")) {
    const Image image = read_image(entry.path());
    EXPECT_EQ(image.width, 48);
    EXPECT_EQ(image.height, 40);
    ++complete;
  }
  EXPECT_LT(complete, 40);
}

}  // namespace
}  // namespace relume
