// An image encoded into memory instead of a file (a frame sent over HTTP): the same encoding as
// write_image (relume/image.hpp) gives a file of that format, byte for byte, with the same checks.
// Implemented in image_io.cpp, beside write_image, which shares the encoder.
#pragma once

#include <relume/image.hpp>
#include <string>

namespace relume {

// The bytes of `image` as a file with this extension (".png", ".jpg", ".exr", ...) written by
// write_image with `options`. Throws Error as write_image does (options that do not fit the
// format, a NaN or Inf pixel, an encoder failure).
std::string encode_image_bytes(const std::string& extension, const Image& image,
                               const ImageWriteOptions& options = {});

}  // namespace relume
