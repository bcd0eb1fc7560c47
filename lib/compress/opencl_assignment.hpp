// The reassignment step of clustered factorization as an OpenCL kernel (kernels/assign.cl): the
// same IRLS fits and choice as the CPU path (lib/compress/cluster_assignment.hpp), one work-item
// per function, on PoCL's CPU device by default or on any GPU. The rows are uploaded once and kept
// on the device while the same rows are assigned again.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "compress/cluster_iterations.hpp"
#include "opencl/runtime.hpp"

namespace relume {

class OpenClAssigner {
 public:
  // device_selector: see select_opencl_device ("" = RELUME_DEVICE, else the default device).
  // light_vector: lights per vector of the kernel's passes, 4, 8 or 16; 0 picks the device's
  // (the native float width on CPUs, clamped to 8..16; 4 on other devices).
  OpenClAssigner(const std::string& device_selector, const IrlsSettings& settings,
                 int light_vector = 0);
  // device: one of list_opencl_devices(), for example to run on each device in turn.
  OpenClAssigner(OpenClDevice device, const IrlsSettings& settings, int light_vector = 0);
  ~OpenClAssigner();

  AssignmentResult assign(const WorkingRows& rows, const ClusterModel& model,
                          const CandidateLists& candidates);
  // assign() as a ClusteringOptions::assign callback (this object must outlive its use).
  AssignFunction function();
  std::string device_label() const;
  int light_vector() const { return light_vector_; }
  double kernel_seconds() const { return kernel_seconds_; }  // summed over all calls

 private:
  std::unique_ptr<OpenClContext> context_;
  IrlsSettings settings_;
  int light_vector_;
  // The rows last uploaded, identified by their address, size and a sample of their values.
  const float* uploaded_rows_ = nullptr;
  std::size_t uploaded_count_ = 0;
  double uploaded_sample_ = 0;
  std::optional<cl::Buffer> rows_buffer_;
  double kernel_seconds_ = 0;
};

// The OpenCL assignment on `device_selector` with `clustering`'s weight-fit settings, PoCL's
// threads capped by clustering.threads like the CPU work. Its error says how to go without OpenCL.
std::unique_ptr<OpenClAssigner> make_opencl_assigner(const std::string& device_selector,
                                                     const ClusteringOptions& clustering);

// The assignment `assign` names: "opencl", the OpenCL assigner on `device` (make_opencl_assigner),
// or "cpu", the C++ path (null). Throws Error for another name. Install the assigner's function()
// as clustering.assign; the pointer keeps it alive.
std::unique_ptr<OpenClAssigner> make_assigner(const std::string& assign, const std::string& device,
                                              const ClusteringOptions& clustering);

}  // namespace relume
