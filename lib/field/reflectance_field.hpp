// A fixed-viewpoint reflectance field: one row per reflectance function (pixel x colour channel),
// one column per light. Row p = (y * width + x) * channels + c. Values are float32 and already
// divided by each light's per-channel intensity.
#pragma once

#include <Eigen/Core>
#include <cstdint>
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
  RowMatrixF values;                 // functions x lights
  std::vector<std::uint8_t> mask;    // width * height, 1 = inside the object
  LightDirections directions;        // unit vectors towards each light, camera frame (x right,
                                     // y up, z towards the camera)
  LightRgb intensities;              // per-light RGB the images were divided by (ones if none)
  std::vector<std::string> image_names;  // one per light, for messages and write-back

  int lights() const { return static_cast<int>(values.cols()); }
  std::int64_t functions() const { return values.rows(); }
  std::int64_t pixels() const { return std::int64_t(width) * height; }
  std::int64_t function_index(int x, int y, int c) const {
    return (std::int64_t(y) * width + x) * channels + c;
  }
};

}  // namespace relume
