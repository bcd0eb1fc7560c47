// The chunk structure of a PNG file, checked before OpenImageIO decodes it. For a corrupt PNG,
// libpng printed its own "libpng error: ..." line on stderr beside relume's message (OpenImageIO
// 2.4's error handler returns, and libpng's default one prints). Corruption shows in the chunks:
// a file cut short, a chunk whose bytes no longer match its CRC-32, a length or type that is not
// a chunk's; these are refused here, with relume's message alone.
#pragma once

#include <filesystem>

namespace relume {

// Throws Error "cannot read image PATH: ..." naming the chunk and its byte offset when a chunk's
// type is not four letters, its data runs past the end of the file or fails its CRC-32, or the
// file ends before its IEND chunk. Files that do not start with PNG's signature are left alone.
void check_png_chunks(const std::filesystem::path& path);

}  // namespace relume
