// Implementation of the OpenCL assignment (see opencl_assignment.hpp).
#include "compress/opencl_assignment.hpp"

#include <cstdio>
#include <relume/error.hpp>
#include <string>
#include <utility>

namespace relume {

namespace {

// CPUs run the passes as SIMD vectors of their native float width (PoCL: 8 with AVX2, 16 with
// AVX-512); a GPU work-item keeps its vectors in registers, so short ones suit it.
int default_light_vector(const OpenClDevice& device) {
  if (device.type != "cpu") return 4;
  const cl_uint native = device.device.getInfo<CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT>();
  return native >= 16 ? 16 : 8;
}

}  // namespace

OpenClAssigner::OpenClAssigner(const std::string& device_selector, const IrlsSettings& settings,
                               int light_vector)
    : OpenClAssigner(select_opencl_device(device_selector), settings, light_vector) {}

OpenClAssigner::OpenClAssigner(OpenClDevice device, const IrlsSettings& settings, int light_vector)
    : settings_(settings),
      light_vector_(light_vector ? light_vector : default_light_vector(device)) {
  if (light_vector_ != 4 && light_vector_ != 8 && light_vector_ != 16)
    throw Error("OpenCL assignment: lights per vector must be 4, 8 or 16, got " +
                std::to_string(light_vector_));
  context_ = std::make_unique<OpenClContext>(std::move(device));
}

OpenClAssigner::~OpenClAssigner() = default;

std::string OpenClAssigner::device_label() const { return context_->device().label(); }

AssignFunction OpenClAssigner::function() {
  return [this](const WorkingRows& rows, const ClusterModel& model,
                const CandidateLists& candidates) { return assign(rows, model, candidates); };
}

AssignmentResult OpenClAssigner::assign(const WorkingRows& rows, const ClusterModel& model,
                                        const CandidateLists& candidates) {
  const std::size_t count = rows.rows();
  AssignmentResult result;
  result.best.assign(count, -1);
  result.second.assign(count, -1);
  result.objective.assign(count, 0.0f);
  result.weights.setZero(static_cast<Eigen::Index>(count), model.terms);
  if (count == 0) return result;
  const bool fp64 = context_->device().device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") !=
                    std::string::npos;
  char options[256];
  std::snprintf(options, sizeof options,
                "-DTERMS=%d -DLIGHTS=%d -DWIDTH=%d -DITERATIONS=%d -DEPSILON=%.9gf -DUSE_DOUBLE=%d "
                "-DLIGHT_VECTOR=%d",
                model.terms, model.lights, candidates.width, settings_.iterations,
                double(settings_.epsilon), fp64 ? 1 : 0, light_vector_);
  try {
    const cl::Context& context = context_->context();
    cl::CommandQueue& queue = context_->queue();
    const std::size_t row_bytes = count * model.lights * sizeof(float);
    double sample = 0;
    for (std::size_t i = 0; i < std::size_t(rows.values.size()); i += 997)
      sample += rows.values.data()[i];
    if (!rows_buffer_ || uploaded_rows_ != rows.values.data() || uploaded_count_ != count ||
        uploaded_sample_ != sample) {
      // A CPU device reads the rows where they are: no second copy of the largest array.
      const cl_mem_flags where =
          context_->device().type == "cpu" ? CL_MEM_USE_HOST_PTR : CL_MEM_COPY_HOST_PTR;
      rows_buffer_ = cl::Buffer(context, CL_MEM_READ_ONLY | where, row_bytes,
                                const_cast<float*>(rows.values.data()));
      uploaded_rows_ = rows.values.data();
      uploaded_count_ = count;
      uploaded_sample_ = sample;
    }
    cl::Buffer bases(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                     model.bases.size() * sizeof(float), const_cast<float*>(model.bases.data()));
    cl::Buffer lists(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                     candidates.clusters.size() * sizeof(std::int32_t),
                     const_cast<std::int32_t*>(candidates.clusters.data()));
    cl::Buffer best(context, CL_MEM_WRITE_ONLY, count * sizeof(std::int32_t));
    cl::Buffer second(context, CL_MEM_WRITE_ONLY, count * sizeof(std::int32_t));
    cl::Buffer objective(context, CL_MEM_WRITE_ONLY, count * sizeof(float));
    cl::Buffer weights(context, CL_MEM_WRITE_ONLY, count * model.terms * sizeof(float));
    cl::Kernel kernel = context_->kernel("assign.cl", "assign_rows", options);
    kernel.setArg(0, *rows_buffer_);
    kernel.setArg(1, bases);
    kernel.setArg(2, lists);
    kernel.setArg(3, static_cast<cl_uint>(count));
    kernel.setArg(4, best);
    kernel.setArg(5, second);
    kernel.setArg(6, objective);
    kernel.setArg(7, weights);
    const std::size_t group = 64;
    const std::size_t global = (count + group - 1) / group * group;
    cl::Event done;
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(group),
                               nullptr, &done);
    queue.enqueueReadBuffer(best, CL_FALSE, 0, count * sizeof(std::int32_t), result.best.data());
    queue.enqueueReadBuffer(second, CL_FALSE, 0, count * sizeof(std::int32_t),
                            result.second.data());
    queue.enqueueReadBuffer(objective, CL_FALSE, 0, count * sizeof(float), result.objective.data());
    queue.enqueueReadBuffer(weights, CL_TRUE, 0, count * model.terms * sizeof(float),
                            result.weights.data());
    kernel_seconds_ += event_seconds(done);
  } catch (const cl::Error& error) {
    throw Error("cluster assignment on " + device_label() + ": " + error.what() + " failed with " +
                opencl_error_name(error.err()));
  }
  return result;
}

std::unique_ptr<OpenClAssigner> make_opencl_assigner(const std::string& device_selector,
                                                     const ClusteringOptions& clustering) {
  if (clustering.threads > 0) limit_cpu_driver_threads(clustering.threads);
  try {
    return std::make_unique<OpenClAssigner>(device_selector, clustering.weight_fit);
  } catch (const Error& error) {
    throw Error(std::string(error.what()) +
                " (the assignment runs without OpenCL with --assign cpu, assign = \"cpu\" in the "
                "library and in Python)");
  }
}

std::unique_ptr<OpenClAssigner> make_assigner(const std::string& assign, const std::string& device,
                                              const ClusteringOptions& clustering) {
  if (assign == "cpu") return nullptr;
  if (assign != "opencl") throw Error("--assign must be 'opencl' or 'cpu', got '" + assign + "'");
  return make_opencl_assigner(device, clustering);
}

}  // namespace relume
