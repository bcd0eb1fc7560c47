// Relighting of a .relume container for the commands: the OpenCL relighter on the chosen device
// (`--device`, RELUME_DEVICE, else a GPU, else PoCL's CPU device), or with `--cpu` the plain C++
// reference. Shared by `relight` and `relight-sequence`.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "model/compressed_field.hpp"
#include "image/image.hpp"

namespace relume {

struct RendererOptions {
  std::string device;
  bool cpu_reference = false;
  std::string residual = "all";  // "all", N entries, or P% of the lights
};

void add_renderer_options(CLI::App& command, RendererOptions& options);

class CompressedRenderer {
 public:
  CompressedRenderer(const CompressedField& field, const RendererOptions& options);
  ~CompressedRenderer();

  // One image per light vector, with the residual cap from the options (or `residual_cap`).
  std::vector<Image> render(const std::vector<LightRgb>& lights);
  std::vector<Image> render(const std::vector<LightRgb>& lights, int residual_cap);

  int residual_cap() const { return residual_cap_; }
  std::string device_name() const;
  // Bytes and device seconds of the kernels of the last render call (0 for the CPU reference).
  double last_kernel_bytes() const;
  double last_kernel_seconds() const;

 private:
  struct Backend;
  std::unique_ptr<Backend> backend_;
  int residual_cap_;
};

}  // namespace relume
