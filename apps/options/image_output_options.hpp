// How `relight` and `relight-sequence` write images: `--exposure STOPS|auto` (integer outputs),
// `--bits 8|16` (PNG, TIFF) and `--half` (EXR), resolved to relume::ImageWriteOptions. auto
// exposes by the lit object (image/auto_exposure.hpp); a sequence resolves it on its first frame
// and keeps it, so the frames do not flicker.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

struct ImageOutputOptions {
  std::string exposure = "0";  // stops, or "auto"
  int bits = 0;
  bool half = false;
};

void add_image_output_options(CLI::App& command, ImageOutputOptions& options);

// Throws Error when the options do not fit `path` (before any work is done); notes that an
// exposure given for a float output leaves it unexposed.
void check_image_output(const std::filesystem::path& path, const ImageOutputOptions& options);

// The exposure in stops of a display-referred (integer or video) output of `image`: the given
// number, or for auto measured inside `mask` (empty: everywhere) and noted.
double display_exposure(const ImageOutputOptions& options, const Image& image,
                        const std::vector<std::uint8_t>& mask);

// The write options for `image` to `path`; auto exposure is measured on `image` inside `mask`
// (empty: everywhere) and noted, for integer outputs only (floats are written unexposed).
ImageWriteOptions resolve_image_output(const std::filesystem::path& path,
                                       const ImageOutputOptions& options, const Image& image,
                                       const std::vector<std::uint8_t>& mask);

}  // namespace relume
