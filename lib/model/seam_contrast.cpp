// The seam contrast of a relit image against the model's cluster map (see seam_contrast.hpp).
#include "model/seam_contrast.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <relume/error.hpp>

#include "image/image_difference.hpp"
#include "model/compressed_field_checks.hpp"

namespace relume {
namespace {

constexpr int gradient_bins = 2 * seam_gradient_octaves + 1;

// Sums of the error changes of one kind of pair, per gradient bin.
struct BinnedChanges {
  std::array<double, gradient_bins> sum{};
  std::array<std::size_t, gradient_bins> count{};
};

// Bin 0: gradients up to P 2^-20; then half octaves up to P (and above, in the last bin).
int gradient_bin(double gradient, double lowest) {
  if (lowest <= 0 || gradient <= lowest) return 0;
  return std::min(gradient_bins - 1, 1 + int(std::floor(2 * std::log2(gradient / lowest))));
}

// The ratio and its two sums, for one channel or pooled.
struct ContrastSums {
  double border_changes = 0, expected_changes = 0;
  std::size_t compared = 0;

  void add(const BinnedChanges& same, const BinnedChanges& border) {
    for (int b = 0; b < gradient_bins; ++b) {
      if (same.count[b] == 0 || same.sum[b] <= 0 || border.count[b] == 0) continue;
      border_changes += border.sum[b];
      expected_changes += double(border.count[b]) * same.sum[b] / double(same.count[b]);
      compared += border.count[b];
    }
  }
  std::optional<double> ratio() const {
    return expected_changes > 0 ? std::optional<double>(border_changes / expected_changes)
                                : std::nullopt;
  }
};

}  // namespace

SeamContrast seam_contrast(const Image& image, const Image& reference, const CompressedField& model,
                           const std::vector<std::uint8_t>& area, const std::string& image_label,
                           const std::string& reference_label, const std::string& model_label) {
  if (model.width != image.width || model.height != image.height ||
      model.channels != image.channels)
    throw Error(model_label + " is " +
                size_and_channels_text(model.width, model.height, model.channels) + ", " +
                image_label + " is " +
                size_and_channels_text(image.width, image.height, image.channels));
  check_mask(model, model_label);
  check_functions(model, model_label);
  check_clusters(model, model_label);
  check_comparable(image, reference, image_label, reference_label, area);
  const int width = image.width, height = image.height, channels = image.channels;
  const std::vector<std::uint8_t>& inside = area.empty() ? model.mask : area;
  std::vector<std::int64_t> cluster_of(std::size_t(model.functions()), -1);
  for (std::size_t row = 0; row < model.stored_rows(); ++row)
    cluster_of[model.stored_function[row]] = model.cluster[row];

  SeamContrast result;
  double peak = 0;
  for (std::size_t p = 0; p < inside.size(); ++p)
    if (inside[p])
      for (int c = 0; c < channels; ++c)
        peak = std::max(peak, double(std::abs(reference.pixels[p * channels + c])));
  const double lowest = peak * std::ldexp(1.0, -seam_gradient_octaves);

  ContrastSums pooled;
  for (int c = 0; c < channels; ++c) {
    BinnedChanges same, border;
    const auto add_pair = [&](std::size_t p, std::size_t q) {
      if (!inside[p] || !inside[q]) return;
      const std::int64_t cluster_p = cluster_of[p * channels + c];
      const std::int64_t cluster_q = cluster_of[q * channels + c];
      if (cluster_p < 0 || cluster_q < 0) return;
      const double r_p = reference.pixels[p * channels + c],
                   r_q = reference.pixels[q * channels + c];
      const double error_p = image.pixels[p * channels + c] - r_p;
      const double error_q = image.pixels[q * channels + c] - r_q;
      BinnedChanges& kind = cluster_p == cluster_q ? same : border;
      const int bin = gradient_bin(std::abs(r_p - r_q), lowest);
      kind.sum[bin] += std::abs(error_p - error_q);
      ++kind.count[bin];
      ++(cluster_p == cluster_q ? result.same_pairs : result.border_pairs);
    };
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t p = std::size_t(y) * width + x;
        if (x + 1 < width) add_pair(p, p + 1);
        if (y + 1 < height) add_pair(p, p + width);
      }
    ContrastSums channel;
    channel.add(same, border);
    pooled.add(same, border);
    result.per_channel.push_back(channel.ratio());
  }
  result.contrast = pooled.ratio();
  result.compared_border_pairs = pooled.compared;

  for (std::size_t p = 0; p < inside.size(); ++p) {
    if (!inside[p]) continue;
    const std::int64_t* clusters = &cluster_of[p * channels];
    if (std::any_of(clusters, clusters + channels, [](std::int64_t k) { return k < 0; })) continue;
    ++result.pixels_with_every_channel_stored;
    if (std::any_of(clusters, clusters + channels,
                    [&](std::int64_t k) { return k != clusters[0]; }))
      ++result.pixels_with_split_channels;
  }
  return result;
}

}  // namespace relume
