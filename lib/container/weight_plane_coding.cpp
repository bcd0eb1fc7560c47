// Implementation of W's camera-domain coding (see weight_plane_coding.hpp).
#include "container/weight_plane_coding.hpp"

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>

#include "container/jpeg2000_planes.hpp"
#include "model/weight_planes.hpp"

namespace relume {
namespace {

// The largest plane value becomes this integer: headroom below 32767 for the wavelet's ringing.
constexpr double largest_integer = 32000;

}  // namespace

QuantizedWeightPlanes quantize_weight_planes(const CompressedField& field) {
  const std::vector<float> values = weight_planes(field);
  double largest = 0;
  for (const float v : values) {
    if (!std::isfinite(v))
      throw Error("cannot code the weights as planes: a weight is " + std::to_string(v));
    largest = std::max(largest, double(std::abs(v)));
  }
  QuantizedWeightPlanes quantized;
  quantized.step = float(std::max(largest, 1e-30) / largest_integer);
  quantized.planes = {field.width, field.height, field.channels * field.terms, {}};
  quantized.planes.samples.resize(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    quantized.planes.samples[i] = std::int32_t(std::lround(double(values[i]) / quantized.step));
  return quantized;
}

void code_quantized_planes(CompressedField& field, const QuantizedWeightPlanes& quantized,
                           std::uint64_t max_bytes, unsigned threads) {
  field.coded_weights.codestream = encode_jpeg2000_planes(quantized.planes, max_bytes, threads);
  field.coded_weights.step = quantized.step;
  decode_weight_planes(field, threads, "the weight planes just coded");
}

void code_weights_as_planes(CompressedField& field, std::uint64_t max_bytes, unsigned threads) {
  code_quantized_planes(field, quantize_weight_planes(field), max_bytes, threads);
}

void decode_weight_planes(CompressedField& field, unsigned threads, const std::string& where) {
  const CodedWeights& coded = field.coded_weights;
  if (!(std::isfinite(coded.step) && coded.step > 0))
    throw Error(where + ": the weight planes' step is " + std::to_string(coded.step) +
                ", expected a positive number");
  const IntegerPlanes planes =
      decode_jpeg2000_planes(coded.codestream.data(), coded.codestream.size(), field.width,
                             field.height, field.channels * field.terms, threads, where);
  set_weights_from_integer_planes(field, planes.samples, coded.step);
}

}  // namespace relume
