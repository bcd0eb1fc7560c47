// Files read and written at offsets (lib/core/disk_file.hpp): a temporary lives as long as its
// object (also when moved), a created file stays for its owner, and reads beyond what was written
// fail naming the file.
#include "core/disk_file.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {
namespace fs = std::filesystem;

TEST(DiskFile, ATemporaryIsWrittenAtOffsetsAndGoesWithItsObject) {
  testing::TempDir dir;
  fs::path path;
  {
    DiskFile moved_from = DiskFile::temporary(dir / "scratch", "out.raw", "raw section");
    const DiskFile file = std::move(moved_from);
    path = file.path();
    EXPECT_EQ(path.filename().string().rfind(".tmp-", 0), 0u) << path;
    EXPECT_EQ(path.parent_path(), dir / "scratch");
  }
  EXPECT_FALSE(fs::exists(path)) << "a moved temporary is removed once";

  DiskFile file = DiskFile::temporary(dir.path(), "out.raw", "raw section");
  file.append("abcdef", 6);
  file.write_at(2, "XY", 2);
  file.append("gh", 2);
  EXPECT_EQ(file.size(), 8u);
  std::string back(8, '\0');
  file.read_at(0, back.data(), back.size());
  EXPECT_EQ(back, "abXYefgh");
  try {
    file.read_at(6, back.data(), 4);
    ADD_FAILURE() << "read beyond the 8 bytes written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("raw section " + file.path().string()), std::string::npos)
        << e.what();
  }
}

TEST(DiskFile, ACreatedFileStaysForItsOwner) {
  testing::TempDir dir;
  {
    DiskFile file = DiskFile::create(dir / "a.relume", "container");
    file.append("123", 3);
    file.close();
  }
  EXPECT_EQ(read_file(dir / "a.relume"), "123");
  EXPECT_THROW(DiskFile::create(dir / "missing" / "a.relume", "container"), Error);
}

}  // namespace
}  // namespace relume
