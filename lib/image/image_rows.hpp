// Reading an image a band of rows at a time through OpenImageIO (scanline reads, or the tiles
// that cover the band), decoded as read_image decodes a whole file: for fields larger than
// memory, whose light images are read in lockstep strip by strip (field/field_strips.hpp).
// read_image is this reader over all rows.
#pragma once

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <relume/image.hpp>

namespace relume {

class ImageRowReader {
 public:
  // Opens `path`; throws Error naming it when it cannot be read or has no pixels.
  ImageRowReader(const std::filesystem::path& path, const ImageReadOptions& options);

  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  int channels() const { return spec_.nchannels; }
  int source_bits() const;  // the file's integer depth (8, 16, ...), 0 for floats
  const std::filesystem::path& path() const { return path_; }

  // Rows [first, first + count) into `pixels` (count x width x channels floats, interleaved),
  // 8-bit values sRGB-decoded when the options say so. Throws Error naming the file for rows out
  // of range or a decoding failure.
  void read_rows(int first, int count, float* pixels);

 private:
  std::filesystem::path path_;
  std::unique_ptr<OIIO::ImageInput> input_;
  OIIO::ImageSpec spec_;
  bool srgb_ = false;
};

}  // namespace relume
