// Relighting of a compressed reflectance field with OpenCL (kernels/relight.cl). The field is
// uploaded once in the kernels' layout; each call then uploads only the light vectors, runs the
// per-cluster GEMV (v_k = F^k . I) and the per-row kernel (W . v + the first `cap` residual
// entries . I), and reads the images back. A batch of B light vectors is relit in one pass over
// W and E. Every call records its kernels' device times and the bytes they move.
#pragma once

#include <cstdint>
#include <map>
#include <relume/compressed_field.hpp>
#include <relume/image.hpp>
#include <string>
#include <vector>

#include "opencl/runtime.hpp"
#include "relight/compressed_relight_reference.hpp"
#include "relight/relight_layout.hpp"

namespace relume {

// One kernel launch: "gemv" (cluster_products), "rows" (relight_rows), "spmv" (residual_rows),
// "dark" (dark_pixels) or "ceiling" (relight_rows as the work ceiling).
struct KernelTiming {
  std::string kernel;
  double seconds = 0;       // device time from the profiling events
  std::uint64_t bytes = 0;  // global memory the launch reads and writes (capped residual only)
  std::uint64_t flops = 0;  // floating-point operations: two per multiply-add, padding included

  double gbps() const { return seconds > 0 ? 1e-9 * double(bytes) / seconds : 0; }
};

// What the last relighting call did.
struct RelightTiming {
  int frames = 0;
  std::vector<KernelTiming> kernels;  // in launch order
  double wall_seconds = 0;            // the whole call: light upload, kernels and image read-back

  double kernel_seconds() const;
  std::uint64_t kernel_bytes() const;
  std::uint64_t kernel_flops() const;
  const KernelTiming& kernel(const std::string& name) const;  // throws Error when absent
};

struct OpenClRelighterOptions {
  // Rows per slice of the W and residual layout (SLICE_ROWS, lib/relight/relight_layout.hpp); 0: on
  // CPU devices the tallest of 4096, 2048, ... rows whose padding adds at most 1/8 to the head's
  // residual entries (tall_slice_rows), 32 (a warp) on others. W lies in blocks of 16 rows on
  // CPU devices (at most the slice), in whole slices on others.
  int slice_rows = 0;
  // CPU devices: residual entries per row in the slices; the rest lie in groups of one row
  // vector. 0: 24. Other devices keep every entry in the slices.
  int head_entries = 0;
  int work_group_rows = 0;  // rows per work-group; 0: 1024 on CPU devices, 64 on others
  int max_batch = 32;       // frames per pass; longer batches are relit in passes of this size
  // Rows per work-item of single-frame passes (vector loads and gathers: ROW_VECTOR); 0: 16 on
  // CPU devices, 1 on others. Must be 1, 4, 8 or 16 and divide the slice rows.
  int row_vector = 0;
};

class OpenClRelighter {
 public:
  // Checks the field (check_relightable) and that its layout fits the memory budget
  // (check_relight_memory), and uploads it. The context must outlive the relighter; the field
  // need not.
  OpenClRelighter(OpenClContext& context, const CompressedField& field,
                  const OpenClRelighterOptions& options = {});

  // One relit image; at most residual_cap >= 0 residual entries per row are used
  // (all_residual_entries: every entry).
  Image relight(const LightRgb& light, int residual_cap = all_residual_entries);
  // One image per light vector, relit in passes of up to max_batch frames.
  std::vector<Image> relight_batch(const std::vector<LightRgb>& lights,
                                   int residual_cap = all_residual_entries);
  // The residual term E . I alone (the residual SpMV), as an image.
  Image relight_residual(const LightRgb& light, int residual_cap = all_residual_entries);

  // The same, writing into caller-owned images: `images` is resized to one image per light
  // vector, and an image that already has the field's size keeps its storage, so a sequence or
  // a benchmark loop allocates nothing per frame.
  void relight_batch_into(const std::vector<LightRgb>& lights, int residual_cap,
                          std::vector<Image>& images);
  void relight_residual_into(const LightRgb& light, int residual_cap, Image& image);
  // The per-cluster GEMV alone: v[(k * terms + j) * channels + c].
  std::vector<float> cluster_products(const LightRgb& light);
  // The relighter's work ceiling (kernels/relight.cl, WORK_CEILING): device seconds of the row
  // kernel relighting `frames` frames at this cap with every read kept in a cached window and
  // nothing written, i.e. what its gathers, conversions and multiply-adds take without the memory
  // traffic. Leaves the relighter as it was (the next call relights as before).
  double work_ceiling_seconds(int frames, int residual_cap);

  const RelightTiming& last_timing() const { return last_timing_; }
  // The layout in use: the options as resolved for this device and field.
  int slice_rows() const { return slice_rows_; }
  int weight_rows() const { return weight_rows_; }
  int work_group_rows() const { return int(work_group_rows_); }
  int row_vector() const { return row_vector_; }
  // Residual entries per row in the slices (the rest in row-vector groups); unlimited off CPUs.
  std::uint32_t head_entries() const { return head_entries_; }
  // Bytes per weight and per residual value on the device: 4 (float), 2 (int16) or 1 (int8).
  int weight_bytes() const { return weight_bytes_; }
  int residual_value_bytes() const { return residual_value_bytes_; }
  // Field data held on the device, in bytes.
  std::uint64_t device_bytes() const { return device_bytes_; }
  // Entries of the longest residual row, and the share of stored residual slots that are zero
  // padding (slices are as wide as their longest row).
  int widest_residual_row() const { return widest_row_; }
  double residual_padding() const;
  // Bytes the row kernel reads from the residual arrays with this cap.
  std::uint64_t residual_bytes(int residual_cap) const;

  const OpenClContext& context() const { return context_; }

 private:
  struct BatchProgram {
    int batch = 0;
    int batch_pad = 0;
    cl::Kernel gemv;
    cl::Kernel relight_rows;
    cl::Kernel residual_rows;
    cl::Kernel dark_pixels;
    cl::Kernel ceiling_rows;  // built at the first work_ceiling_seconds
    std::string options;      // the programs' build options
    cl::Buffer light;         // lights_even * channels * batch_pad
    cl::Buffer dark;          // channels * batch_pad: each frame's dark-model value per channel
    std::vector<float> dark_staging;  // host copy of `dark` while it is being written
    cl::Buffer products;              // clusters * terms * channels * batch_pad
    cl::Buffer output;                // batch * frame_stride_, zero where no row is stored
    std::vector<float> staging;       // host copy of `light` while it is being written
  };
  struct Launch {
    KernelTiming timing;  // seconds filled in once the launch has finished
    cl::Event event;
  };
  enum class Pass { relight, residual, products, ceiling };

  BatchProgram& batch_program(int batch);
  void upload_lights(BatchProgram& program, const std::vector<const LightRgb*>& lights, Pass pass);
  Launch launch_gemv(BatchProgram& program);
  Launch launch_rows(BatchProgram& program, Pass pass, int residual_cap);
  Launch launch_dark(BatchProgram& program);
  double work_ceiling_pass_seconds(int frames, int residual_cap);
  // Relights lights into images[first, first + lights.size()).
  void run_pass(const std::vector<const LightRgb*>& lights, int residual_cap, Pass pass,
                Image* images);
  std::uint64_t light_buffer_bytes(const BatchProgram& program) const;
  bool reads_tail(int residual_cap) const;  // whether a cap reaches past the head
  std::uint64_t products_bytes(const BatchProgram& program) const;

  OpenClContext& context_;
  CompressedField shape_;  // the field's sizes and transform; its arrays stay empty
  OpenClRelighterOptions options_;
  std::size_t rows_ = 0;
  int lights_even_ = 0;
  int cluster_id_bytes_ = 4;
  int light_id_bytes_ = 4;
  int weight_bytes_ = 4;          // W as the device holds it: float, int16 or int8
  int residual_value_bytes_ = 4;  // likewise the residual values
  float residual_scale_ = 1;      // the light vector's factor on upload (relight_layout.hpp)
  float products_scale_ = 1;      // the blocks' factor: weight step / residual_scale_
  std::string base_options_;
  std::size_t work_group_rows_ = 0;
  int row_vector_ = 1;
  int slice_rows_ = 32;
  int weight_rows_ = 32;  // rows per block of W (relight_layout.hpp)
  int window_rows_ = 32;  // rows whose data the work ceiling reads (WINDOW_ROWS)
  int tail_rows_ = 0;
  std::uint32_t head_entries_ = 0xffffffffu;
  std::uint64_t frame_stride_ = 0;  // floats between frames in the output buffers

  cl::Buffer stored_function_;
  cl::Buffer cluster_;
  cl::Buffer weights_;
  cl::Buffer blocks_;
  cl::Buffer slice_offsets_;
  cl::Buffer tail_offsets_;
  cl::Buffer residual_values_;
  cl::Buffer residual_lights_;
  cl::Buffer dark_runs_;   // (first pixel, pixels, its dark index) of each run of dark pixels
  cl::Buffer dark_gains_;  // dark pixels x channels
  std::size_t dark_run_count_ = 0;
  std::uint64_t dark_pixel_count_ = 0;
  std::vector<float> dark_;     // the field's dark model, channels x lights
  ResidualRegion head_, tail_;  // the residual's layout (their offsets are uploaded too)
  int widest_row_ = 0;
  std::uint64_t stored_entries_ = 0;  // residual slots on the device, padding included
  std::uint64_t nonzeros_ = 0;
  std::uint64_t device_bytes_ = 0;

  std::map<int, BatchProgram> programs_;
  RelightTiming last_timing_;
};

}  // namespace relume
