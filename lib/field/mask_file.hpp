// Object masks on disk: an image of the field's size whose non-zero pixels are inside (any
// channel; DiLiGenT's mask.png). The same rule serves field folders, `--mask FILE` for any input
// and `compare --mask`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace relume {

// width * height entries, 1 = inside. Throws Error naming the file when it cannot be read or its
// size differs from width x height.
std::vector<std::uint8_t> read_mask(const std::filesystem::path& path, int width, int height);

}  // namespace relume
