// `relume devices`: lists every OpenCL device of every platform and marks the one that
// `--device`-less commands use (RELUME_DEVICE, else the first GPU, else PoCL's CPU device).
#include <cstdio>
#include <cstdlib>

#include "command_registry.hpp"
#include "opencl/runtime.hpp"

namespace relume {
namespace {

void run_devices() {
  const auto devices = list_opencl_devices();
  if (devices.empty()) {
    std::printf("no OpenCL device found (for CPUs install pocl-opencl-icd)\n");
    return;
  }
  const OpenClDevice chosen = select_opencl_device();
  std::printf("  %-3s %-32s %-40s %-5s %5s %9s  %s\n", "#", "platform", "device", "type", "units",
              "memory", "version");
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const auto& device = devices[i];
    const bool is_chosen = device.device() == chosen.device();
    std::printf("%c %-3zu %-32s %-40s %-5s %5u %6.1f GiB  %s\n", is_chosen ? '*' : ' ', i,
                device.platform_name.c_str(), device.device_name.c_str(), device.type.c_str(),
                device.compute_units, double(device.global_memory_bytes) / (1ull << 30),
                device.version.c_str());
  }
  const char* environment = std::getenv("RELUME_DEVICE");
  std::printf(
      "* = used by default (%s); choose another with --device TEXT or RELUME_DEVICE=TEXT,\n"
      "    TEXT being a case-insensitive part of \"platform / device\"\n",
      environment && *environment ? "from RELUME_DEVICE" : "first GPU, else PoCL CPU");
}

const CommandRegistration registration{80, [](CLI::App& app) {
                                         auto* command = app.add_subcommand(
                                             "devices", "List the OpenCL platforms and devices");
                                         command->callback([] { run_devices(); });
                                       }};

}  // namespace
}  // namespace relume
