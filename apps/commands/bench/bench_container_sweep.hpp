// The residual points of `relume bench --container`, as in the paper's Table 1: 0, 3, 5, 10, 20
// and 30% of the lights, each turned into a per-row cap as `relume relight --residual P%` does,
// and the full residual; each with the error (paper Eq. 16) of the field relit with that cap.
#pragma once

#include <filesystem>
#include <relume/compressed_field.hpp>
#include <string>
#include <vector>

#include "commands/bench/bench_records.hpp"

namespace relume {

struct ContainerSweep {
  CompressedField field;  // read from the container
  std::vector<ResidualPoint> points;
};

// Reads the container at `container_path` and makes its points. The error is measured against
// the container with its full residual when `original_field` is empty, else against the field
// loaded from `original_field` (a field folder or .lp file) over the container's mask. Throws
// Error naming both files when their shapes differ. The device-only build
// (device_only/container_sweep_unavailable.cpp) has no containers: it throws Error saying so.
ContainerSweep container_sweep(const std::filesystem::path& container_path,
                               const std::string& original_field, unsigned threads);

}  // namespace relume
