// The parts of a compression run's JSON report beside compression_report's core: the plan, the
// streamed passes, the cost of the stored precision, and the one-line summary users read.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "compress/compression_plan.hpp"
#include "compress/storage_precision.hpp"
#include "compress/streamed_compression.hpp"

namespace relume {

nlohmann::ordered_json plan_json(const CompressionPlan& plan);

nlohmann::ordered_json streamed_json(const StreamedTrace& trace);

// What the stored precision cost: the precisions, bits, the error stored against float32 and the
// quantization chosen (its steps, the sample's errors, the terms per cluster). `report` is the
// run's report so far (its error_masked); `quantization_error` is NaN when not measured.
nlohmann::ordered_json precision_cost_json(const nlohmann::ordered_json& report,
                                           const CompressedField& stored,
                                           const ContainerOptions& container,
                                           const StoragePrecision& precision,
                                           const std::optional<QuantizationChoice>& quantization,
                                           double error_masked_float32, double quantization_error);

// One line for users, leading with the error over what is stored (paper Eq. 16 over the
// functions inside the mask); with a mask, the whole frame's error follows, in which every
// background function, not stored, counts as entirely lost. Ending with fewer clusters than asked
// is said with the reason (clusters of too few functions merged, or too few functions).
std::string summary_line(const nlohmann::ordered_json& report, int clusters);

}  // namespace relume
