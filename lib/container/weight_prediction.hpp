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

// weights: stored rows x terms integers (row-major), each in [-32767, 32767]. stored[k * terms +
// j] says whether the rows of cluster k store term j (model/cluster_terms.hpp: the container
// stores no weight for an all-zero basis row); the errors of the stored terms only, in row
// order, are returned. The weights of terms that are not stored must be 0: they are predicted
// from as zeros.
std::vector<std::uint16_t> predict_weights(const CompressedField& field,
                                           const std::vector<std::int32_t>& weights,
                                           const std::vector<std::uint8_t>& stored);

// The inverse: all stored rows x terms integers, zero where not stored, from the stored
// prediction errors (field.stored_function and field.cluster must be set). Throws Error unless
// `errors` holds exactly one value per stored term.
std::vector<std::int32_t> unpredict_weights(const CompressedField& field,
                                            const std::vector<std::uint16_t>& errors,
                                            const std::vector<std::uint8_t>& stored);

// The number of weights a field stores: sum over stored rows of the terms their cluster stores.
std::uint64_t stored_weight_count(const CompressedField& field,
                                  const std::vector<std::uint8_t>& stored);

}  // namespace relume
