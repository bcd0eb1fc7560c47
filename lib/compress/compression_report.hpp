// The JSON report of one `relume compress` run: time per phase, iterations with their L1
// objective, bytes per container section and the ratio to the float32 input, the error of paper
// Eq. 16 over all functions and over the masked ones (also at shorter residual prefixes), the
// 8-bit PSNR over the whole frame and inside the mask (lib/model/field_psnr.hpp), the worst
// per-light error relative to each function's peak and the negative values of the masked
// functions (lib/model/per_light_error.hpp), bytes per pixel,
// sparseness of the residual at several thresholds (paper Fig. 4d) and peak memory.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "compress/clustered_factorization.hpp"
#include "compress/field_errors.hpp"
#include "container/container.hpp"

namespace relume {

struct CompressionReportInputs {
  std::string input, output;
  const CompressedField* compressed = nullptr;  // as stored
  FieldErrors errors;                           // of `compressed` against the original
  const CompressionOptions* options = nullptr;
  const CompressionStats* stats = nullptr;
  ContainerLayout layout;
  // Phases outside compress_field (load, write, error_measure, the streamed passes).
  std::map<std::string, double> extra_seconds;
  double total_seconds = 0;
  unsigned threads = 0;
  std::string solver;
  std::string assignment_device;  // "cpu" or the OpenCL device label
  double psnr_white = 1.0;        // the field value that is 255 in the 8-bit PSNR
};

// The compression parameters recorded in the container header (a JSON object).
nlohmann::ordered_json compression_parameters(const CompressionOptions& options,
                                              const CompressionStats& stats,
                                              const std::string& solver);

nlohmann::ordered_json compression_report(const CompressionReportInputs& run);

// Peak resident memory of this process so far, in bytes (getrusage).
std::uint64_t peak_memory_bytes();

}  // namespace relume
