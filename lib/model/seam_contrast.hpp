// Seam contrast: whether the borders between a compressed field's clusters show in a relit image.
// Each stored function (pixel x channel) belongs to one cluster; the relit error a - r of
// neighbouring pixels changes more across a border than inside a cluster when the borders show.
//
// Per channel c, every 4-neighbour pair of pixels (p, q) inside the compared area whose channel-c
// functions are both stored (dark-model pixels and functions without a row have no cluster and
// are left out) is a *border pair* when the two functions have different clusters and a *same
// pair* otherwise. A pair's error change is |(a - r)(p) - (a - r)(q)| in channel c. The error
// changes more where the reference does, so pairs are binned by their reference gradient
// |r(p) - r(q)|: half-octave bins below the reference's peak value P (the largest value of any
// channel in the area), from P 2^-20 up, and one bin below that. Then
//   seam contrast = sum of the border pairs' error changes
//                   / sum over bins of (border pairs in the bin x mean error change of the same
//                     pairs in the bin),
// pooled over the channels (and per channel): how much larger the error jumps across borders are
// than inside clusters at the same reference gradient. 1.0: the borders do not show. Border pairs
// in a bin without same pairs (or whose same pairs all have zero change) are left out.
//
// A pixel whose channels are stored in different clusters has independent errors per channel,
// which shows as colour: their count is reported too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/image.hpp>
#include <string>
#include <vector>

namespace relume {

struct SeamContrast {
  std::optional<double> contrast;                    // nullopt: no border pair could be compared
  std::vector<std::optional<double>> per_channel;    // the same per channel
  std::size_t same_pairs = 0, border_pairs = 0;      // counted over the channels
  std::size_t compared_border_pairs = 0;             // those in bins with same pairs
  std::size_t pixels_with_every_channel_stored = 0;  // inside the area
  std::size_t pixels_with_split_channels = 0;        // of those, channels not all in one cluster
};

inline constexpr int seam_gradient_octaves = 20;

// `image`, `reference`: relit images of the model's size and channels (`image` from `model`);
// `area`: width * height entries, 1 = compared; empty: the model's mask. Throws Error naming the
// labels when the images do not fit each other, the area or the model.
SeamContrast seam_contrast(const Image& image, const Image& reference, const CompressedField& model,
                           const std::vector<std::uint8_t>& area = {},
                           const std::string& image_label = "image",
                           const std::string& reference_label = "reference",
                           const std::string& model_label = "the model");

}  // namespace relume
