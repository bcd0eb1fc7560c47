// Implementation of OpenCL device discovery, device choice and the program cache.
#include "opencl/runtime.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <relume/error.hpp>

#include "core/atomic_file.hpp"
#include "opencl/kernel_sources.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return text;
}

std::string trimmed(std::string text) {
  while (!text.empty() &&
         (std::isspace(static_cast<unsigned char>(text.back())) || text.back() == '\0'))
    text.pop_back();
  return text;
}

std::string device_type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "gpu";
  if (type & CL_DEVICE_TYPE_CPU) return "cpu";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

bool environment_flag(const char* name) {
  const char* value = std::getenv(name);
  return value && *value && std::strcmp(value, "0") != 0;
}

std::string device_listing(const std::vector<OpenClDevice>& devices) {
  std::string text;
  for (const auto& device : devices) text += "\n  " + device.label();
  return text.empty() ? "\n  (no OpenCL device found)" : text;
}

}  // namespace

std::string OpenClDevice::label() const { return platform_name + " / " + device_name; }

void limit_cpu_driver_threads(unsigned threads) {
  setenv("POCL_MAX_PTHREAD_COUNT", std::to_string(threads).c_str(), /*overwrite=*/0);
}

std::vector<OpenClDevice> list_opencl_devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    return {};  // the ICD loader reports CL_PLATFORM_NOT_FOUND_KHR when nothing is installed
  }
  std::vector<OpenClDevice> devices;
  for (const auto& platform : platforms) {
    std::vector<cl::Device> platform_devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &platform_devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices
    }
    for (const auto& device : platform_devices) {
      OpenClDevice entry;
      entry.platform = platform;
      entry.device = device;
      entry.platform_name = trimmed(platform.getInfo<CL_PLATFORM_NAME>());
      entry.device_name = trimmed(device.getInfo<CL_DEVICE_NAME>());
      entry.type = device_type_name(device.getInfo<CL_DEVICE_TYPE>());
      entry.version = trimmed(device.getInfo<CL_DEVICE_VERSION>());
      entry.driver_version = trimmed(device.getInfo<CL_DRIVER_VERSION>());
      entry.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      entry.global_memory_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      entry.max_work_group_size = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
      devices.push_back(std::move(entry));
    }
  }
  return devices;
}

std::size_t default_opencl_device_index(const std::vector<OpenClDevice>& devices) {
  if (devices.empty())
    throw Error("no OpenCL device found: install an OpenCL driver (for CPUs: pocl-opencl-icd)");
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (devices[i].type == "gpu") return i;
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (devices[i].type == "cpu" &&
        lowercase(devices[i].platform_name).find("portable computing language") !=
            std::string::npos)
      return i;
  return 0;
}

std::vector<std::size_t> matching_opencl_devices(const std::vector<OpenClDevice>& devices,
                                                 const std::string& selector) {
  const std::string wanted = lowercase(selector);
  std::vector<std::size_t> matches;
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (lowercase(devices[i].label()).find(wanted) != std::string::npos) matches.push_back(i);
  return matches;
}

OpenClDevice select_opencl_device(const std::string& selector) {
  const std::vector<OpenClDevice> devices = list_opencl_devices();
  std::string chosen = selector;
  std::string origin = "--device";
  if (chosen.empty()) {
    const char* environment = std::getenv("RELUME_DEVICE");
    if (environment && *environment) {
      chosen = environment;
      origin = "RELUME_DEVICE";
    }
  }
  if (chosen.empty()) return devices[default_opencl_device_index(devices)];
  const auto matches = matching_opencl_devices(devices, chosen);
  if (matches.empty())
    throw Error(origin + " '" + chosen +
                "' matches no OpenCL device (expected a substring of one of these):" +
                device_listing(devices));
  return devices[matches.front()];
}

std::string opencl_program_key(const std::string& source, const OpenClDevice& device,
                               const std::string& options) {
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bits
  const auto mix = [&hash](const std::string& text) {
    for (const unsigned char ch : text) {
      hash ^= ch;
      hash *= 1099511628211ull;
    }
    hash ^= 0xff;  // separator, so that ("ab", "c") and ("a", "bc") differ
    hash *= 1099511628211ull;
  };
  mix(source);
  mix(device.platform_name);
  mix(device.device_name);
  mix(device.driver_version);
  mix(options);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::optional<fs::path> opencl_program_cache_dir() {
  if (const char* folder = std::getenv("RELUME_KERNEL_CACHE")) {
    if (lowercase(folder) == "off" || !*folder) return std::nullopt;
    return fs::path(folder);
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "relume" / "kernels";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "relume" / "kernels";
  return std::nullopt;
}

std::string opencl_error_name(cl_int code) {
  static const std::map<cl_int, const char*> names = {
      {CL_DEVICE_NOT_FOUND, "CL_DEVICE_NOT_FOUND"},
      {CL_DEVICE_NOT_AVAILABLE, "CL_DEVICE_NOT_AVAILABLE"},
      {CL_COMPILER_NOT_AVAILABLE, "CL_COMPILER_NOT_AVAILABLE"},
      {CL_MEM_OBJECT_ALLOCATION_FAILURE, "CL_MEM_OBJECT_ALLOCATION_FAILURE"},
      {CL_OUT_OF_RESOURCES, "CL_OUT_OF_RESOURCES"},
      {CL_OUT_OF_HOST_MEMORY, "CL_OUT_OF_HOST_MEMORY"},
      {CL_BUILD_PROGRAM_FAILURE, "CL_BUILD_PROGRAM_FAILURE"},
      {CL_INVALID_VALUE, "CL_INVALID_VALUE"},
      {CL_INVALID_DEVICE, "CL_INVALID_DEVICE"},
      {CL_INVALID_BINARY, "CL_INVALID_BINARY"},
      {CL_INVALID_BUILD_OPTIONS, "CL_INVALID_BUILD_OPTIONS"},
      {CL_INVALID_KERNEL_NAME, "CL_INVALID_KERNEL_NAME"},
      {CL_INVALID_KERNEL_ARGS, "CL_INVALID_KERNEL_ARGS"},
      {CL_INVALID_ARG_SIZE, "CL_INVALID_ARG_SIZE"},
      {CL_INVALID_WORK_GROUP_SIZE, "CL_INVALID_WORK_GROUP_SIZE"},
      {CL_INVALID_GLOBAL_WORK_SIZE, "CL_INVALID_GLOBAL_WORK_SIZE"},
      {CL_INVALID_BUFFER_SIZE, "CL_INVALID_BUFFER_SIZE"},
      {CL_INVALID_MEM_OBJECT, "CL_INVALID_MEM_OBJECT"},
      {CL_INVALID_OPERATION, "CL_INVALID_OPERATION"},
  };
  const auto found = names.find(code);
  return std::string(found == names.end() ? "OpenCL error" : found->second) + " (" +
         std::to_string(code) + ")";
}

OpenClContext::OpenClContext(OpenClDevice device)
    : device_(std::move(device)),
      context_(device_.device),
      queue_(context_, device_.device, CL_QUEUE_PROFILING_ENABLE) {}

const cl::Program& OpenClContext::program(const std::string& source_name,
                                          const std::string& options) {
  const auto& sources = kernel_sources();
  const auto source = sources.find(source_name);
  if (source == sources.end())
    throw Error("no embedded OpenCL source kernels/" + source_name +
                " (expected a file in kernels/ at build time)");
  // In memory the exact name and options are the key (the embedded source of a name is fixed).
  const std::string memory_key = source_name + '\n' + options;
  if (const auto cached = programs_.find(memory_key); cached != programs_.end())
    return cached->second;
  const std::string key = opencl_program_key(source->second, device_, options);

  if (environment_flag("RELUME_DUMP_KERNELS"))
    std::fprintf(stderr, "relume: building kernels/%s for %s with options '%s' (key %s):\n%s\n",
                 source_name.c_str(), device_.label().c_str(), options.c_str(), key.c_str(),
                 source->second.c_str());

  const auto cache_dir = opencl_program_cache_dir();
  const fs::path cache_file = cache_dir ? *cache_dir / (key + ".bin") : fs::path();
  std::error_code missing;
  if (cache_dir && fs::exists(cache_file, missing)) {
    if (auto loaded = load_cached_binary(cache_file, options)) {
      ++loaded_from_disk_;
      return programs_.emplace(memory_key, std::move(*loaded)).first->second;
    }
  }

  cl::Program program(context_, source->second);
  try {
    program.build(std::vector<cl::Device>{device_.device}, options.c_str());
  } catch (const cl::Error& error) {
    std::string log;
    try {
      log = trimmed(program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_.device));
    } catch (const cl::Error&) {
      log = "(no build log available)";
    }
    throw Error("building kernels/" + source_name + " failed on " + device_.label() +
                " with options '" + options + "': " + opencl_error_name(error.err()) +
                "\nbuild log:\n" + log);
  }
  ++built_from_source_;
  if (cache_dir) store_binary(program, cache_file);
  return programs_.emplace(memory_key, std::move(program)).first->second;
}

cl::Kernel OpenClContext::kernel(const std::string& source_name, const std::string& kernel_name,
                                 const std::string& options) {
  const cl::Program& built = program(source_name, options);
  try {
    return cl::Kernel(built, kernel_name.c_str());
  } catch (const cl::Error& error) {
    throw Error("kernels/" + source_name + " has no kernel '" + kernel_name +
                "': " + opencl_error_name(error.err()));
  }
}

std::optional<cl::Program> OpenClContext::load_cached_binary(const fs::path& file,
                                                             const std::string& options) {
  try {
    const std::string bytes = read_file(file);
    cl::Program::Binaries binaries{std::vector<unsigned char>(bytes.begin(), bytes.end())};
    cl::Program program(context_, {device_.device}, binaries);
    program.build(std::vector<cl::Device>{device_.device}, options.c_str());
    return program;
  } catch (const std::exception&) {
    // A stale or damaged cache entry: drop it and build from source.
    std::error_code ignored;
    fs::remove(file, ignored);
    return std::nullopt;
  }
}

void OpenClContext::store_binary(const cl::Program& program, const fs::path& file) {
  try {
    const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    if (binaries.size() != 1 || binaries.front().empty()) return;
    fs::create_directories(file.parent_path());
    write_file_atomically(file, std::string(binaries.front().begin(), binaries.front().end()));
  } catch (const std::exception& error) {
    // The cache only saves build time: say why it could not be written and go on.
    std::fprintf(stderr, "relume: warning: cannot write the kernel cache %s: %s\n",
                 file.string().c_str(), error.what());
  }
}

double event_seconds(const cl::Event& event) {
  const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return 1e-9 * static_cast<double>(end - start);
}

}  // namespace relume
