// The working state of clustered factorization: the rows being clustered (each reflectance
// function scaled to unit L2 norm, in the chosen basis transform), one cluster per row, the
// cluster bases F^k and each row's weights. Scaling rows to unit norm makes the clustering
// invariant to brightness and matches the per-function relative error of paper Eq. 16; the scale
// goes back into W and E when the compressed field is built.
#pragma once

#include <cstdint>
#include <relume/field.hpp>
#include <string>
#include <vector>

#include "compress/noise_model.hpp"

namespace relume {

struct WorkingRows {
  RowMatrixF values;         // rows x lights, every row of unit L2 norm
  std::vector<float> norms;  // each row's original L2 norm (> 0)
  // Each row's pixel when the rows are a field's colour channels (the rows of a pixel are
  // consecutive); empty: the rows are unrelated.
  std::vector<std::uint32_t> pixel;

  int lights() const { return static_cast<int>(values.cols()); }
  std::size_t rows() const { return static_cast<std::size_t>(values.rows()); }
  const float* row(std::size_t r) const { return values.data() + r * values.cols(); }
};

struct ClusterModel {
  int terms = 0;
  int lights = 0;
  int clusters = 0;
  std::vector<float> bases;              // clusters x terms x lights (F^k row j at k*t + j)
  std::vector<std::int32_t> assignment;  // cluster of every working row
  RowMatrixF weights;                    // rows x terms, for the assigned cluster

  float* basis(int k) { return bases.data() + std::size_t(k) * terms * lights; }
  const float* basis(int k) const { return bases.data() + std::size_t(k) * terms * lights; }
  // Members of every cluster, in ascending row order.
  std::vector<std::vector<std::uint32_t>> members() const;
};

// The rows a compressed field stores: functions whose pixel is inside the mask (every pixel when
// the mask is empty) and that are not all zero, in ascending function order, each transformed to
// `transform`'s basis and scaled to unit norm.
struct PreparedRows {
  WorkingRows rows;
  std::vector<std::uint32_t> functions;  // working row -> function index p
  // Light weighting (compress/light_weighting.hpp): the rows are R[p,i] / light_scale[i] before
  // they are scaled to unit norm; empty: R itself.
  std::vector<float> light_scale;
  // Pixels inside the mask whose every channel is, within the noise model's threshold, a
  // multiple of the dark shape (noise_model.hpp), with the multiple its block's (dark_gains.hpp):
  // they get no rows and relight as gain x `dark` (channels x lights, the dark shape in the rows'
  // basis). dark_gains: dark pixels x channels, multiples of dark_gain_step.
  std::vector<std::uint32_t> dark_pixels;
  std::vector<float> dark;
  std::vector<float> dark_gains;
  float dark_gain_step = 0;
};

// Throws Error for a mask of the wrong size, and naming the first function (pixel, channel) and
// light inside the mask that holds NaN or Inf; values outside the mask are never read.
void check_finite_values(const ReflectanceField& field);

// The functions a compression stores: inside the mask, not all zero, not of a dark pixel (by
// `noise`, measured on R itself), divided by `light_scale` per light when it is not empty, scaled
// to unit norm, in the Haar basis if asked (not together with a light scale). Throws Error
// naming the function and light of a NaN or Inf value.
PreparedRows prepare_rows(const ReflectanceField& field, bool haar_transform,
                          const NoiseModel& noise, unsigned threads,
                          const std::vector<float>& light_scale = {});

}  // namespace relume
