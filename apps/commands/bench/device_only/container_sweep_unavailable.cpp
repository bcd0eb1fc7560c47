// `relume bench --container` in the device-only build (RELUME_DEVICE_BENCH_ONLY,
// cmake/device_bench.cmake), which has no container reader and no image I/O: it says so. The
// full build links apps/commands/bench/bench_container_sweep.cpp instead.
#include <relume/error.hpp>

#include "commands/bench/bench_container_sweep.hpp"

namespace relume {

ContainerSweep container_sweep(const std::filesystem::path& container_path,
                               const std::string& /*original_field*/, unsigned /*threads*/) {
  throw Error("--container " + container_path.string() +
              ": this relume is the device-only build (scripts/build_device_bench.sh), which "
              "reads no containers or images; bench a container with the full build");
}

}  // namespace relume
