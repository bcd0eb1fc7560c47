// Implementation of band-of-rows image reading (see image_rows.hpp).
#include "image/image_rows.hpp"

#include <algorithm>
#include <relume/error.hpp>
#include <string>
#include <vector>

#include "core/memory_budget.hpp"
#include "image/image_encoding.hpp"
#include "image/png_chunks.hpp"

namespace relume {

ImageRowReader::ImageRowReader(const std::filesystem::path& path, const ImageReadOptions& options)
    : path_(path) {
  if (!std::filesystem::exists(path)) throw Error("image not found: " + path.string());
  check_png_chunks(path);
  input_ = OIIO::ImageInput::open(path.string());
  if (!input_) throw Error("cannot read image " + path.string() + ": " + OIIO::geterror());
  spec_ = input_->spec();
  if (spec_.width <= 0 || spec_.height <= 0 || spec_.nchannels <= 0)
    throw Error("image " + path.string() + " has no pixels");
  const bool eight_bit = spec_.format.basetype == OIIO::TypeDesc::UINT8;
  srgb_ = eight_bit && (options.eight_bit == EightBitEncoding::srgb ||
                        (options.eight_bit == EightBitEncoding::automatic &&
                         !is_linear_color_space(spec_.get_string_attribute("oiio:ColorSpace"))));
}

int ImageRowReader::source_bits() const {
  return spec_.format.is_floating_point() ? 0 : int(spec_.format.size()) * 8;
}

void ImageRowReader::read_rows(int first, int count, float* pixels) {
  if (first < 0 || count < 0 || first + count > spec_.height)
    throw Error("image " + path_.string() + ": rows " + std::to_string(first) + " to " +
                std::to_string(first + count) + " are outside its " + std::to_string(spec_.height) +
                " rows");
  if (count == 0) return;
  const int y0 = spec_.y + first;
  bool read = false;
  if (spec_.tile_width == 0) {
    read = input_->read_scanlines(0, 0, y0, y0 + count, 0, 0, spec_.nchannels,
                                  OIIO::TypeDesc::FLOAT, pixels);
  } else {
    // Tiled: the whole tiles that cover the band, then the band's rows out of them.
    const int tile = spec_.tile_height;
    const int begin = spec_.y + (first / tile) * tile;
    const int end =
        std::min(spec_.y + spec_.height, spec_.y + ((first + count + tile - 1) / tile) * tile);
    const std::size_t row_values = std::size_t(spec_.width) * spec_.nchannels;
    check_memory_need(std::uint64_t(end - begin) * row_values * sizeof(float),
                      "the tiles of image " + path_.string());
    std::vector<float> tiles(std::size_t(end - begin) * row_values);
    read = input_->read_tiles(0, 0, spec_.x, spec_.x + spec_.width, begin, end, spec_.z,
                              spec_.z + std::max(1, spec_.depth), 0, spec_.nchannels,
                              OIIO::TypeDesc::FLOAT, tiles.data());
    if (read)
      std::copy_n(tiles.begin() + std::ptrdiff_t(std::size_t(y0 - begin) * row_values),
                  std::size_t(count) * row_values, pixels);
  }
  if (!read) throw Error("cannot decode image " + path_.string() + ": " + input_->geterror());
  if (!srgb_) return;
  const std::size_t values = std::size_t(count) * spec_.width * spec_.nchannels;
  for (std::size_t i = 0; i < values; ++i) pixels[i] = srgb_to_linear(pixels[i]);
}

}  // namespace relume
