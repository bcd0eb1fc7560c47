// Tests of the PNG chunk check (image/png_chunks.hpp): a PNG cut short, one with a changed byte
// and one with a broken chunk type are refused by relume's message alone, naming the chunk and
// its byte, where libpng added its own "libpng error" line; an intact PNG still reads.
#include "image/png_chunks.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

class PngChunks : public ::testing::Test {
 protected:
  void SetUp() override {
    Image image(24, 16, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 37) / 36;
    write_image(good_, image);
    bytes_ = file_bytes(good_);
    idat_ = bytes_.find("IDAT") - 4;  // the chunk starts at its length
    ASSERT_LT(idat_, bytes_.size());
  }
  testing::TempDir folder_;
  const std::filesystem::path good_ = folder_ / "good.png";
  const std::filesystem::path bad_ = folder_ / "bad.png";
  std::string bytes_;
  std::size_t idat_ = 0;
};

TEST_F(PngChunks, AnIntactPngPassesAndReads) {
  EXPECT_NO_THROW(check_png_chunks(good_));
  EXPECT_EQ(read_image(good_).width, 24);
}

TEST_F(PngChunks, ACutShortPngIsNamedAsOne) {
  write_bytes(bad_, bytes_.substr(0, idat_ + 20));
  EXPECT_EQ(testing::error_message([&] { read_image(bad_); }),
            "cannot read image " + bad_.string() + ": a corrupt PNG: chunk 'IDAT' at byte " +
                std::to_string(idat_) + " needs " +
                std::to_string(bytes_.find("IEND") - 4 - idat_ - 12) +
                " bytes of data, the file ends at byte " + std::to_string(idat_ + 20) +
                ": it was cut short");
  write_bytes(bad_, bytes_.substr(0, bytes_.size() - 12));  // without IEND
  EXPECT_THAT(testing::error_message([&] { read_image(bad_); }),
              HasSubstr("before its last chunk (IEND): it was cut short"));
}

TEST_F(PngChunks, AChangedByteAndABrokenChunkTypeAreNamed) {
  std::string changed = bytes_;
  changed[idat_ + 10] ^= 0x5A;
  write_bytes(bad_, changed);
  EXPECT_EQ(testing::error_message([&] { read_image(bad_); }),
            "cannot read image " + bad_.string() + ": a corrupt PNG: chunk 'IDAT' at byte " +
                std::to_string(idat_) + " does not match its CRC-32: its bytes were changed");
  std::string typeless = bytes_;
  typeless[idat_ + 6] = '\0';
  typeless[idat_ + 7] = '\0';
  write_bytes(bad_, typeless);
  EXPECT_THAT(testing::error_message([&] { read_image(bad_); }),
              HasSubstr("chunk 'ID[00][00]' at byte " + std::to_string(idat_) +
                        " has no chunk type (four letters)"));
}

// The command says relume's message alone: libpng's own line is never printed.
TEST_F(PngChunks, ACommandReportsACorruptPngWithoutLibpngLines) {
  std::string changed = bytes_;
  changed[idat_ + 6] = '\0';
  write_bytes(bad_, changed);
  const auto result =
      testing::run_relume("compare '" + bad_.string() + "' '" + good_.string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_THAT(result.output, HasSubstr("cannot read image " + bad_.string() + ": a corrupt PNG"));
  EXPECT_THAT(result.output, Not(HasSubstr("libpng")));
}

}  // namespace
}  // namespace relume
