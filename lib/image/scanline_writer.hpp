// A float image written strip by strip of scanlines (OpenImageIO's write_scanlines), for outputs
// too large to hold whole: `relume decompress` writes every light's image of a field this way,
// one strip of rows at a time, with all of them open at once.
#pragma once

#include <filesystem>
#include <memory>

namespace relume {

class ScanlineWriter {
 public:
  // Opens `path` (a float format: EXR, TIFF, PFM, HDR) for a width x height image of `channels`
  // float channels. Throws Error naming the path when it cannot.
  ScanlineWriter(const std::filesystem::path& path, int width, int height, int channels);
  ~ScanlineWriter();
  ScanlineWriter(const ScanlineWriter&) = delete;
  ScanlineWriter& operator=(const ScanlineWriter&) = delete;

  // Rows [first_row, first_row + rows), row-major, channels interleaved. Rows come in order.
  // Throws Error naming the path and pixel of a NaN or Inf value, or a failed write.
  void write_rows(int first_row, int rows, const float* pixels);
  // Finishes the file; throws Error naming the path unless every row was written.
  void close();

 private:
  struct Output;
  std::unique_ptr<Output> output_;
  std::filesystem::path path_;
  int width_, height_, channels_, next_row_ = 0;
};

}  // namespace relume
