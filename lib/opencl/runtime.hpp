// The OpenCL runtime: device discovery on every platform, device choice (`--device` or
// RELUME_DEVICE, else the first GPU, else PoCL's CPU device), and a context per device that builds
// the embedded kernels/*.cl programs once and caches them, in memory per context and on disk
// (VexCL style: the file name hashes source, device, driver and build options).
// RELUME_DUMP_KERNELS=1 prints each source before it is built; a failed build throws an Error with
// the source name and the build log.
#pragma once

#include <CL/opencl.hpp>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace relume {

struct OpenClDevice {
  cl::Platform platform;
  cl::Device device;
  std::string platform_name;
  std::string device_name;
  std::string type;            // "gpu", "cpu", "accelerator" or "other"
  std::string version;         // CL_DEVICE_VERSION
  std::string driver_version;  // CL_DRIVER_VERSION
  unsigned compute_units = 0;
  std::uint64_t global_memory_bytes = 0;
  std::size_t max_work_group_size = 0;

  // "platform / device": the text a selector is matched against.
  std::string label() const;
};

// Asks PoCL's CPU driver to run kernels on at most `threads` threads (POCL_MAX_PTHREAD_COUNT),
// unless that variable is set already. Takes effect only before the process's first OpenCL call.
void limit_cpu_driver_threads(unsigned threads);

// Every device of every platform, in platform then device order. Empty when no OpenCL platform
// is installed.
std::vector<OpenClDevice> list_opencl_devices();

// Index into `devices` of the device used when nothing is asked for: the first GPU, else the
// first CPU device of PoCL, else the first device. Throws Error when `devices` is empty.
std::size_t default_opencl_device_index(const std::vector<OpenClDevice>& devices);

// Indices of the devices whose label contains `selector` (case-insensitive), in listing order.
std::vector<std::size_t> matching_opencl_devices(const std::vector<OpenClDevice>& devices,
                                                 const std::string& selector);

// The device named by `selector`, else by RELUME_DEVICE, else the default one. A selector is a
// case-insensitive substring of "platform / device"; the first match wins. Throws Error naming
// the selector and listing the devices when nothing matches.
OpenClDevice select_opencl_device(const std::string& selector = "");

// Hex key of a built program: a 64-bit FNV-1a hash of source, platform, device, driver version
// and build options.
std::string opencl_program_key(const std::string& source, const OpenClDevice& device,
                               const std::string& options);

// Folder of the on-disk program cache: RELUME_KERNEL_CACHE if set ("off" disables the cache),
// else $XDG_CACHE_HOME/relume/kernels, else $HOME/.cache/relume/kernels. nullopt when disabled or
// no home folder is known.
std::optional<std::filesystem::path> opencl_program_cache_dir();

// "CL_OUT_OF_RESOURCES (-5)" for an OpenCL error code.
std::string opencl_error_name(cl_int code);

// One device with its context, an in-order profiling queue and the programs built on it.
class OpenClContext {
 public:
  explicit OpenClContext(OpenClDevice device);

  const OpenClDevice& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // kernels/<source_name> built with `options`, from the in-memory cache, the disk cache or the
  // source (in that order). Throws Error with the source name and build log when it fails.
  const cl::Program& program(const std::string& source_name, const std::string& options = "");
  cl::Kernel kernel(const std::string& source_name, const std::string& kernel_name,
                    const std::string& options = "");

  // How many programs were compiled from source and how many loaded from the disk cache.
  int programs_built_from_source() const { return built_from_source_; }
  int programs_loaded_from_disk() const { return loaded_from_disk_; }

 private:
  std::optional<cl::Program> load_cached_binary(const std::filesystem::path& file,
                                                const std::string& options);
  void store_binary(const cl::Program& program, const std::filesystem::path& file);

  OpenClDevice device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::map<std::string, cl::Program> programs_;  // "source name\noptions" -> built program
  int built_from_source_ = 0;
  int loaded_from_disk_ = 0;
};

// Seconds between the start and the end of a finished, profiled command.
double event_seconds(const cl::Event& event);

}  // namespace relume
