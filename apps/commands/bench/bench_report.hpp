// What `relume bench` is asked to do (its options) and what it relights, and the parts of its
// JSON report that describe them: the field, the residual sweep and each device.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/relight.hpp>
#include <string>
#include <vector>

#include "commands/bench/bench_records.hpp"
#include "model/random_compressed_field.hpp"
#include "opencl/runtime.hpp"
#include "relight/opencl_relighter.hpp"

namespace relume {

struct BenchOptions {
  std::vector<std::string> devices;
  std::string json;
  std::vector<int> frames{16};  // batch sizes of the batched relight
  int repeats = 9;
  int residual_cap = all_residual_entries;
  RandomFieldShape shape;
  std::string precision = "float32";  // of the random field's W and residual values
  std::string container;
  std::string original_field;
  int assign_rows = 16384;
  int assign_candidates = 3;
  std::uint64_t ceiling_mib = 256;
  bool reference = true;
  unsigned threads = 0;
  OpenClRelighterOptions relighter;
};

// The field relit, the residual points it is relit at and whether the GEMV and SpMV get records
// of their own (only for the random field).
struct RelightSubject {
  CompressedField field;
  std::vector<ResidualPoint> points;
  bool with_parts = true;
};

nlohmann::ordered_json field_json(const BenchOptions& options, const CompressedField& field);

nlohmann::ordered_json sweep_json(const BenchOptions& options, const RelightSubject& subject);

// What the report says of a benched device: its names, driver and size.
nlohmann::ordered_json device_json(const OpenClDevice& device);

}  // namespace relume
