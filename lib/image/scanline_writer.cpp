// Implementation of the strip-by-strip float image writer over OpenImageIO.
#include "image/scanline_writer.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <relume/error.hpp>
#include <relume/image.hpp>
#include <relume/version.hpp>
#include <string>

namespace relume {

struct ScanlineWriter::Output {
  std::unique_ptr<OIIO::ImageOutput> image;
};

ScanlineWriter::ScanlineWriter(const std::filesystem::path& path, int width, int height,
                               int channels)
    : output_(std::make_unique<Output>()),
      path_(path),
      width_(width),
      height_(height),
      channels_(channels) {
  if (!is_float_image_format(path))
    throw Error("cannot write " + path.string() + " in strips: not a float image format");
  output_->image = OIIO::ImageOutput::create(path.string());
  if (!output_->image)
    throw Error("no image writer for " + path.string() + ": " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  spec.attribute("Software", version_line());
  // EXR: zip per scanline, not per block of 16: with every light's image open at once, the
  // compressors' buffers are 16 times smaller (0.75 MB against 47 KB an image 320 pixels wide).
  spec.attribute("compression", "zips");
  if (!output_->image->open(path.string(), spec))
    throw Error("cannot write " + path.string() + ": " + output_->image->geterror());
}

ScanlineWriter::~ScanlineWriter() = default;

void ScanlineWriter::write_rows(int first_row, int rows, const float* pixels) {
  if (first_row != next_row_ || rows < 0 || first_row + rows > height_)
    throw Error("cannot write rows " + std::to_string(first_row) + " to " +
                std::to_string(first_row + rows) + " of " + path_.string() + ": row " +
                std::to_string(next_row_) + " of " + std::to_string(height_) + " comes next");
  const std::size_t values = std::size_t(rows) * width_ * channels_;
  for (std::size_t v = 0; v < values; ++v)
    if (!std::isfinite(pixels[v])) {
      const std::size_t pixel = v / channels_;
      throw Error("refusing to write " + path_.string() + ": pixel (" +
                  std::to_string(pixel % width_) + ", " +
                  std::to_string(first_row + pixel / width_) + ") channel " +
                  std::to_string(v % channels_) + " is " + std::to_string(pixels[v]));
    }
  if (rows > 0 && !output_->image->write_scanlines(first_row, first_row + rows, 0,
                                                   OIIO::TypeDesc::FLOAT, pixels))
    throw Error("cannot write " + path_.string() + ": " + output_->image->geterror());
  next_row_ += rows;
}

void ScanlineWriter::close() {
  if (next_row_ != height_)
    throw Error("cannot finish " + path_.string() + ": " + std::to_string(next_row_) + " of " +
                std::to_string(height_) + " rows written");
  if (!output_->image->close())
    throw Error("cannot write " + path_.string() + ": " + output_->image->geterror());
}

}  // namespace relume
