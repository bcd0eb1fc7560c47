// Tests of the OpenCL runtime on PoCL: device listing and choice (substring, RELUME_DEVICE,
// default), the in-memory and on-disk program caches, build failures that name the source and
// carry the build log, and RELUME_DUMP_KERNELS.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <relume/error.hpp>

#include "opencl/kernel_sources.hpp"
#include "opencl/runtime.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

// Sets an environment variable for the life of the object, then restores the old value.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? ::setenv(name, value, 1) : ::unsetenv(name);
  }
  ~ScopedEnvironment() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(OpenClRuntime, ListsThePoclCpuDeviceAndUsesItByDefault) {
  const auto devices = list_opencl_devices();
  ASSERT_FALSE(devices.empty());
  const auto pocl = matching_opencl_devices(devices, "Portable Computing Language");
  ASSERT_FALSE(pocl.empty()) << "PoCL is expected on the test machine";
  EXPECT_EQ(devices[pocl.front()].type, "cpu");
  EXPECT_GT(devices[pocl.front()].compute_units, 0u);
  EXPECT_GT(devices[pocl.front()].global_memory_bytes, 0u);
  const std::size_t chosen = default_opencl_device_index(devices);
  bool has_gpu = false;
  for (const auto& device : devices) has_gpu = has_gpu || device.type == "gpu";
  EXPECT_EQ(devices[chosen].type, has_gpu ? "gpu" : "cpu");
  EXPECT_THROW(default_opencl_device_index({}), Error);
}

TEST(OpenClRuntime, SelectsBySubstringIgnoringCase) {
  ScopedEnvironment no_environment("RELUME_DEVICE", nullptr);
  const OpenClDevice device = select_opencl_device("pORTABLE computing");
  EXPECT_EQ(device.platform_name, "Portable Computing Language");
  EXPECT_NE(device.label().find(device.device_name), std::string::npos);
  try {
    select_opencl_device("no-such-device-anywhere");
    FAIL() << "an unknown selector must be refused";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no-such-device-anywhere"), std::string::npos) << message;
    EXPECT_NE(message.find("--device"), std::string::npos) << message;
    EXPECT_NE(message.find(device.label()), std::string::npos) << "lists the devices: " << message;
  }
}

TEST(OpenClRuntime, RelumeDeviceChoosesWhenNoSelectorIsGiven) {
  {
    ScopedEnvironment environment("RELUME_DEVICE", "no-such-device-anywhere");
    try {
      select_opencl_device();
      FAIL() << "RELUME_DEVICE naming no device must be refused";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("RELUME_DEVICE"), std::string::npos);
    }
    // An explicit selector wins over the environment.
    EXPECT_EQ(select_opencl_device("portable").platform_name, "Portable Computing Language");
  }
  ScopedEnvironment environment("RELUME_DEVICE", "pthread");
  EXPECT_NE(select_opencl_device().device_name.find("pthread"), std::string::npos);
}

TEST(OpenClRuntime, ProgramKeysDependOnSourceDeviceAndOptions) {
  const OpenClDevice device = select_opencl_device("portable");
  const std::string key = opencl_program_key("kernel source", device, "-DA=1");
  EXPECT_EQ(key.size(), 16u);
  EXPECT_EQ(key, opencl_program_key("kernel source", device, "-DA=1"));
  EXPECT_NE(key, opencl_program_key("kernel source", device, "-DA=2"));
  EXPECT_NE(key, opencl_program_key("kernel sourcE", device, "-DA=1"));
  OpenClDevice other = device;
  other.device_name += "x";
  EXPECT_NE(key, opencl_program_key("kernel source", other, "-DA=1"));
}

TEST(OpenClRuntime, CachesBuiltProgramsPerContextInMemory) {
  ScopedEnvironment no_disk_cache("RELUME_KERNEL_CACHE", "off");
  OpenClContext context(select_opencl_device("portable"));
  const cl::Program& first = context.program("ceiling.cl", "-DRUN_LENGTH=8");
  const cl::Program& again = context.program("ceiling.cl", "-DRUN_LENGTH=8");
  EXPECT_EQ(first(), again());
  const cl::Program& other = context.program("ceiling.cl", "-DRUN_LENGTH=4");
  EXPECT_NE(first(), other());
  EXPECT_EQ(context.programs_built_from_source(), 2);
  EXPECT_EQ(context.programs_loaded_from_disk(), 0);
  EXPECT_NO_THROW(context.kernel("ceiling.cl", "copy_blocked", "-DRUN_LENGTH=8"));
}

TEST(OpenClRuntime, BuildFailuresNameTheSourceAndCarryTheBuildLog) {
  ScopedEnvironment no_disk_cache("RELUME_KERNEL_CACHE", "off");
  OpenClContext context(select_opencl_device("portable"));
  try {
    context.program("relight.cl", "-DBATCH_WIDTH=3");  // relight.cl refuses it with #error
    FAIL() << "the build must fail";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("kernels/relight.cl"), std::string::npos) << message;
    EXPECT_NE(message.find("-DBATCH_WIDTH=3"), std::string::npos) << message;
    EXPECT_NE(message.find("BATCH_WIDTH must be 1, 2, 4, 8 or 16"), std::string::npos) << message;
  }
  EXPECT_THROW(context.program("no_such_file.cl"), Error);
  EXPECT_THROW(context.kernel("ceiling.cl", "no_such_kernel"), Error);
}

TEST(OpenClRuntime, ReusesProgramBinariesFromTheDiskCache) {
  testing::TempDir cache;
  ScopedEnvironment disk_cache("RELUME_KERNEL_CACHE", cache.path().c_str());
  const OpenClDevice device = select_opencl_device("portable");
  const std::string options = "-DRUN_LENGTH=2";
  const std::filesystem::path file =
      cache / (opencl_program_key(kernel_sources().at("ceiling.cl"), device, options) + ".bin");
  {
    OpenClContext context(device);
    context.program("ceiling.cl", options);
    EXPECT_EQ(context.programs_built_from_source(), 1);
  }
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  {
    OpenClContext context(device);
    context.program("ceiling.cl", options);
    EXPECT_EQ(context.programs_built_from_source(), 0);
    EXPECT_EQ(context.programs_loaded_from_disk(), 1);
  }
  {
    std::ofstream damaged(file, std::ios::binary | std::ios::trunc);
    damaged << "not a program binary";
  }
  OpenClContext context(device);
  EXPECT_NO_THROW(context.kernel("ceiling.cl", "read_sum_blocked", options));
  EXPECT_EQ(context.programs_built_from_source(), 1) << "a damaged entry is rebuilt";
  EXPECT_GT(std::filesystem::file_size(file), 100u) << "and written again";
}

TEST(OpenClRuntime, DumpsKernelSourcesWhenAsked) {
  ScopedEnvironment no_disk_cache("RELUME_KERNEL_CACHE", "off");
  ScopedEnvironment dump("RELUME_DUMP_KERNELS", "1");
  OpenClContext context(select_opencl_device("portable"));
  ::testing::internal::CaptureStderr();
  context.program("ceiling.cl", "-DRUN_LENGTH=16");
  const std::string dumped = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(dumped.find("building kernels/ceiling.cl"), std::string::npos) << dumped;
  EXPECT_NE(dumped.find("__kernel void read_sum_blocked"), std::string::npos) << dumped;
}

TEST(OpenClRuntime, NamesOpenClErrorCodes) {
  EXPECT_EQ(opencl_error_name(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES (-5)");
  EXPECT_EQ(opencl_error_name(-9999), "OpenCL error (-9999)");
}

}  // namespace
}  // namespace relume
