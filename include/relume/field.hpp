// relume/field.hpp: a fixed-viewpoint reflectance field, and loading it from disk.
//
// One row per reflectance function (pixel x colour channel), one column per light. Row
// p = (y * width + x) * channels + c. Values are float32 and already divided by each light's
// per-channel intensity.
//
// A field folder (DiLiGenT layout) holds the light images, `filenames.txt` (one image name per
// light; without it, the numbered images 001.png ... in the order of their numbers),
// `light_directions.txt`, optional `light_intensities.txt` (each image is divided by its row, per
// channel) and optional `mask.png` (non-zero = inside). An RTI `.lp` file names its images itself
// (first line N, then `filename x y z`). Images load in parallel; every image must have the same
// size and channel count, and NaN/Inf pixels are refused with the image and pixel named.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using LightDirections = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;
// RGB per light: a light vector I (one column per colour) or per-light intensities.
using LightRgb = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct ReflectanceField {
  int width = 0;
  int height = 0;
  int channels = 0;
  RowMatrixF values;                     // functions x lights
  std::vector<std::uint8_t> mask;        // width * height, 1 = inside the object
  LightDirections directions;            // unit vectors towards each light, camera frame (x right,
                                         // y up, z towards the camera)
  LightRgb intensities;                  // per-light RGB the images were divided by (ones if none)
  std::vector<std::string> image_names;  // one per light, for messages and write-back
  // The quantization step of the images in field units: 1 / (2^bits - 1) for integer images
  // (1/255 for 8 bits, 1/65535 for 16; 1/(255 * 12.92) for sRGB-decoded 8 bits, the step at
  // black), divided by the mean light intensity; 0 for float images.
  // Values below it are noise no compression needs to keep (compress's default noise floor).
  float noise_floor = 0;

  int lights() const { return static_cast<int>(values.cols()); }
  std::int64_t functions() const { return values.rows(); }
  std::int64_t pixels() const { return std::int64_t(width) * height; }
  std::int64_t function_index(int x, int y, int c) const {
    return (std::int64_t(y) * width + x) * channels + c;
  }
};

struct FieldLoadOptions {
  // 8-bit images: automatic decides once per field (float and 16-bit images and DiLiGenT
  // folders linear, other 8-bit images sRGB unless they declare linear), or as asked.
  ImageReadOptions image{EightBitEncoding::automatic};
  unsigned threads = 0;  // 0 = all cores
  // The object mask: the folder's mask.png, or this image instead (for any input, .lp captures
  // too; non-zero = inside). With use_mask false every pixel is inside and nothing is read.
  std::filesystem::path mask_file;
  bool use_mask = true;
  // Called once per light image as it is read, from the loading threads (so it must be
  // thread-safe): progress reporting. Empty: nothing is called.
  std::function<void()> image_loaded;
};

// `path` is a field folder or an .lp file. Throws Error naming the file, line or pixel at fault.
ReflectanceField load_field(const std::filesystem::path& path,
                            const FieldLoadOptions& options = {});

// Writes a field folder that load_field reads back: one EXR per light (001.exr ...),
// filenames.txt, light_directions.txt, light_intensities.txt (the field's intensities; its values
// are written multiplied back by them, so the round trip is exact) and mask.png.
void write_field_folder(const std::filesystem::path& folder, const ReflectanceField& field);

}  // namespace relume
