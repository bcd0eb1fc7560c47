// W stored in the camera domain: the weight planes (model/weight_planes.hpp) as integers of one
// step, coded as one JPEG 2000 codestream (jpeg2000_planes.hpp). The container writes the
// codestream as it is (section 'weight_planes') and decodes it at load into the in-memory W, the
// form the relighters read.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <string>

#include "container/jpeg2000_planes.hpp"

namespace relume {

// W's planes as integers of one step (the largest magnitude 32000 steps), what the codestream
// codes. Throws Error when W holds a value that is not finite.
struct QuantizedWeightPlanes {
  IntegerPlanes planes;
  float step = 0;
};
QuantizedWeightPlanes quantize_weight_planes(const CompressedField& field);

// Codes `quantized` (quantize_weight_planes of `field`) in at most `max_bytes` bytes of
// codestream, as code_weights_as_planes does: a rate search codes the same planes at several
// sizes without quantizing them again.
void code_quantized_planes(CompressedField& field, const QuantizedWeightPlanes& quantized,
                           std::uint64_t max_bytes, unsigned threads);

// Codes `field`'s W in at most `max_bytes` bytes of codestream (more only when no codestream of
// its planes is that small, jpeg2000_planes.hpp): sets field.coded_weights and replaces W by
// exactly what the codestream decodes to. `threads`: 0 = one per core. Throws Error when W holds
// a value that is not finite.
void code_weights_as_planes(CompressedField& field, std::uint64_t max_bytes, unsigned threads);

// W from field.coded_weights (the field's size, channels, terms and stored rows already set).
// Throws Error("<where>: ...") when the codestream does not decode to the field's planes.
void decode_weight_planes(CompressedField& field, unsigned threads, const std::string& where);

}  // namespace relume
