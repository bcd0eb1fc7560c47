// The sensor noise of a field, estimated from the field itself (issue 32: no hand-picked noise
// floor), and the dark test it sets. A whole frame is mostly background that no light reaches:
// there every light image holds the camera's black level and ambient light plus noise, so each
// background pixel's function is a multiple of one shared "dark shape" within the noise. Such a
// pixel needs no stored row: it relights as gain x dark shape, the gain stored at a coarse grid
// (compressed_field.hpp, dark_gain_block).
//
// The noise's standard deviation per channel comes from the finest diagonal wavelet band of the
// light images, where noise is in every coefficient and signal in few. Two estimates, the smaller
// kept: the median absolute coefficient over 0.6745 (Donoho and Johnstone; robust to outliers,
// raised by texture), median over the lights; and the root of the median eigenvalue of the
// coefficients' covariance over the lights (texture varies over the lights in a few directions,
// noise in all of them; robust to texture, so a noiseless field whose pixels are unrelated gets
// no noise). At least the input's quantization noise (step / sqrt(12)). The dark shape of a
// channel is the mean function of the darkest tenth of the pixels. A pixel is dark when, in
// every channel, the RMS over the lights of what its dark-shape multiple leaves is at most
// dark_threshold_sigmas noise deviations (prepare_rows, cluster_model.hpp).
#pragma once

#include <relume/field.hpp>
#include <vector>

namespace relume {

// A pixel's leftover after its dark-shape multiple is noise when its RMS over the lights is at
// most this many noise deviations: with 96 lights the RMS of pure noise is within 1.2 deviations
// of its mean in all but one pixel of a million.
inline constexpr float dark_threshold_sigmas = 3.0f;

// A residual entry is kept only when it stands out of the noise by this many deviations. One
// noise value passes 3 deviations with probability 0.27% (0.26 of a 96-light function's values);
// at 1 deviation 32% of them pass, more than any residual budget keeps, and the entries are the
// camera's noise. On the 16-bit DiLiGenT ball, 3 instead of 1 stores a third fewer bytes at
// 0.3 dB less PSNR inside the mask and 7% more relit squared error, better on both than 3
// entries per function instead of 5 (docs/compression.md, "Residual threshold").
inline constexpr float residual_threshold_sigmas = 3.0f;

struct NoiseModel {
  bool estimated = true;         // false: the thresholds are a noise floor the user gave
  std::vector<float> sigma;      // per channel, field units (empty when a floor was given)
  std::vector<float> threshold;  // per channel; all zero: no pixel is dark
  std::vector<float> shape;      // channels x lights, the dark shape in the light basis
  // false: every dark pixel's gain is 1 (a streamed run sees a strip at a time, not the blocks
  // of gains across strips and ranks), the test made with gain 1.
  bool block_gains = true;
};

// The model of `field` (inside its mask, every pixel when it has none). Float images without
// noise give zero deviations and thresholds: no pixel is dark.
NoiseModel estimate_noise(const ReflectanceField& field, unsigned threads);

// The model of a field read strip by strip: estimated on `first_strip` (the same pixel rows for
// every rank), without block gains.
NoiseModel estimate_streamed_noise(const ReflectanceField& first_strip, float floor,
                                   unsigned threads);

// The user's noise floor instead of the estimate: `floor` for every channel's threshold (0: no
// pixel is dark), the dark shape estimated as above. Throws Error for a negative or non-finite
// floor.
NoiseModel noise_floor_model(const ReflectanceField& field, float floor);

// The residual threshold that goes with the model: entries at the noise level are not worth
// their bytes. residual_threshold_sigmas times the mean of the channels' deviations (the floor
// itself when one was given), at least the input's quantization step.
float default_residual_threshold(const NoiseModel& model, const ReflectanceField& field);

}  // namespace relume
