// Camera-space prediction of quantized weights in the container (the paper's future work:
// neighbouring pixels have similar weights). Each stored row's integer weights are predicted from
// the same channel's rows of the pixels to the left (a), above (b) and above-left (c), term by
// term, with the median edge detector of LOCO-I / JPEG-LS: min(a, b) when c >= max(a, b),
// max(a, b) when c <= min(a, b), else a + b - c; with only a or b stored, that one; with neither,
// 0. The container stores the prediction errors modulo 2^16, which the decoder undoes in the same
// row order. After align_cluster_bases (lib/model/basis_alignment.hpp) the weights mean nearly
// the same in neighbouring clusters, so the prediction also works across cluster borders.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

namespace relume {

// weights: stored rows x terms integers (row-major), each in [-32767, 32767].
std::vector<std::uint16_t> predict_weights(const CompressedField& field,
                                           const std::vector<std::int32_t>& weights);

// The inverse: integers from the stored prediction errors (field.stored_function must be set).
std::vector<std::int32_t> unpredict_weights(const CompressedField& field,
                                            const std::vector<std::uint16_t>& errors);

}  // namespace relume
