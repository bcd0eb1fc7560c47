// Implementation of the test helpers.
#include "support/test_support.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <relume/error.hpp>

#include "model/dark_gains.hpp"

namespace relume::testing {
namespace fs = std::filesystem;

std::string shared_data_hint() {
  const char* env = std::getenv("RELUME_DATA");
  return env ? std::string(env) : std::string(RELUME_DEFAULT_DATA_DIR);
}

std::optional<fs::path> shared_data_dir() {
  const fs::path dir = shared_data_hint();
  if (fs::is_directory(dir / "olat") && fs::is_directory(dir / "envmaps")) return dir;
  return std::nullopt;
}

TempDir::TempDir() {
  std::random_device device;
  path_ = fs::temp_directory_path() / ("relume-test-" + std::to_string(device()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::string error_message(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no relume::Error thrown)";
}

CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) {
    result.exit_code = -1;
    return result;
  }
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    result.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

CommandResult run_relume(const std::string& arguments) {
  return run_command(std::string("RELUME_QUIET=1 '") + RELUME_BINARY + "' " + arguments);
}

TempDir* CommandSuite::folder_ = nullptr;

void CommandSuite::SetUpTestSuite() { folder_ = new TempDir; }

void CommandSuite::TearDownTestSuite() {
  delete folder_;
  folder_ = nullptr;
}

std::string CommandSuite::path(const std::string& name) {
  return (folder_->path() / name).string();
}

CommandResult CommandSuite::run_or_fail(const std::string& arguments) {
  const CommandResult result = run_relume(arguments);
  EXPECT_EQ(result.exit_code, 0) << arguments << "\n" << result.output;
  return result;
}

void CommandSuite::make_small_scene() {
  run_or_fail("synth -o '" + path("scene") + "' --size 24x20 --lights 40 --samples 1");
  run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
              "' --clusters 4 --terms 2 --residual 6");
}

ReflectanceField noisy_original(const CompressedField& compressed, double noise) {
  ReflectanceField field = reconstruct_field(compressed);
  std::uint32_t state = 99;
  for (std::uint32_t p : compressed.stored_function)
    for (int i = 0; i < field.lights(); ++i) {
      state = state * 1664525u + 1013904223u;
      field.values(p, i) += float(noise * (double(state >> 8) / double(1 << 24) - 0.5));
    }
  return field;
}

double relative_squared_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  double difference = 0, energy = 0;
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    difference += (double(a.pixels[i]) - b.pixels[i]) * (double(a.pixels[i]) - b.pixels[i]);
    energy += double(b.pixels[i]) * b.pixels[i];
  }
  return difference / energy;
}

void add_dark_pixels(CompressedField& field) {
  std::vector<std::uint8_t> stored_pixel(field.mask.size(), 0);
  for (const std::uint32_t p : field.stored_function)
    stored_pixel[p / std::uint32_t(field.channels)] = 1;
  for (std::size_t q = 0; q < field.mask.size(); q += 2)
    if (!stored_pixel[q]) {
      field.mask[q] = 1;
      field.dark_pixels.push_back(std::uint32_t(q));
    }
  field.dark.assign(std::size_t(field.channels) * field.lights, 0.0f);
  for (std::size_t v = 0; v < field.dark.size(); ++v) field.dark[v] = 0.001f * float(v % 7);
}

void add_dark_gains(CompressedField& field) {
  field.dark_gain_step = 0.125f;
  DarkGainGrid grid = empty_dark_gain_grid(field.width, field.height, field.channels);
  for (std::size_t v = 0; v < grid.values.size(); ++v) grid.values[v] = std::int32_t(3 + v % 13);
  expand_dark_gains(field, grid);
}

}  // namespace relume::testing
