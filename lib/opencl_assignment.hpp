// The reassignment step of clustered factorization as an OpenCL kernel (kernels/assign.cl): the
// same IRLS fits and choice as the CPU path (lib/cluster_assignment.hpp), one work-item per
// function, on PoCL's CPU device by default or on any GPU. The rows are uploaded once and kept on
// the device while the same rows are assigned again.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "cluster_iterations.hpp"
#include "opencl_runtime.hpp"

namespace relume {

class OpenClAssigner {
 public:
  // device_selector: see select_opencl_device ("" = RELUME_DEVICE, else the default device).
  OpenClAssigner(const std::string& device_selector, const IrlsSettings& settings);
  // device: one of list_opencl_devices(), for example to run on each device in turn.
  OpenClAssigner(OpenClDevice device, const IrlsSettings& settings);
  ~OpenClAssigner();

  AssignmentResult assign(const WorkingRows& rows, const ClusterModel& model,
                          const CandidateLists& candidates);
  // assign() as a ClusteringOptions::assign callback (this object must outlive its use).
  AssignFunction function();
  std::string device_label() const;
  double kernel_seconds() const { return kernel_seconds_; }  // summed over all calls

 private:
  std::unique_ptr<OpenClContext> context_;
  IrlsSettings settings_;
  // The rows last uploaded, identified by their address, size and a sample of their values.
  const float* uploaded_rows_ = nullptr;
  std::size_t uploaded_count_ = 0;
  double uploaded_sample_ = 0;
  std::optional<cl::Buffer> rows_buffer_;
  double kernel_seconds_ = 0;
};

}  // namespace relume
