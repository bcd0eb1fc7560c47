// Reading a field one strip of pixel rows at a time, for fields larger than memory (compress's
// streamed plan): every light image stays open and is read forward in lockstep, a band of rows
// from each, through OpenImageIO scanline (or tile) reads. A strip is a ReflectanceField of its
// own, width x rows pixels with the field's lights, intensities, noise floor and its rows of the
// mask, checked as load_field checks a whole field; its function p is the field's function
// first_row x width x channels + p.
#pragma once

#include <filesystem>
#include <relume/field.hpp>
#include <vector>

#include "image/image_rows.hpp"

namespace relume {

class FieldStripReader {
 public:
  // Opens every light image of the field folder or .lp file `path` (load_field's options; its
  // progress callback is not called). Throws Error naming the file at fault, or the open-file
  // limit when it cannot hold one file per light.
  FieldStripReader(const std::filesystem::path& path, const FieldLoadOptions& options);

  // The field without values: size, channels, lights, light files, mask, noise floor.
  const ReflectanceField& header() const { return header_; }
  const std::filesystem::path& path() const { return path_; }
  int width() const { return header_.width; }
  int height() const { return header_.height; }
  int lights() const { return header_.lights(); }

  // Pixel rows [first_row, first_row + rows): read forward only (first_row at or after the end
  // of the last strip read); rewind() starts over from the top.
  ReflectanceField read(int first_row, int rows);
  void rewind();

 private:
  void open_images();

  std::filesystem::path path_;
  std::vector<std::filesystem::path> images_;
  ImageReadOptions read_options_;
  unsigned threads_ = 0;
  ReflectanceField header_;
  std::vector<ImageRowReader> readers_;
  int next_row_ = 0;
};

// Appends `strip`'s pixel rows [first_row, first_row + rows) below `field`'s (an empty field,
// height 0, takes the strip's shape). Throws Error for another shape or rows outside the strip.
void append_field_rows(ReflectanceField& field, const ReflectanceField& strip, int first_row,
                       int rows);

}  // namespace relume
