// Implementation of the OpenCL relighter: the device layout of the field (see kernels/relight.cl
// for its description), the launches and their byte counts.
#include "relight/opencl_relighter.hpp"

#include <algorithm>
#include <chrono>
#include <relume/error.hpp>

#include "model/reconstruct_field.hpp"
#include "relight/relight_layout.hpp"

namespace relume {
namespace {

constexpr int max_batch_limit = 64;  // private accumulators per work-item stay small

// Smallest unsigned type that holds values below `count`: its byte size.
int index_bytes(std::int64_t count) {
  if (count <= 256) return 1;
  if (count <= 65536) return 2;
  return 4;
}

const char* index_type(int bytes) { return bytes == 1 ? "uchar" : bytes == 2 ? "ushort" : "uint"; }

// Frames per vector in the kernels for a batch of `batch` frames.
int batch_width(int batch) {
  for (int width : {16, 8, 4, 2})
    if (batch >= width) return width;
  return 1;
}

// Packs 32-bit indices into `bytes`-wide little-endian integers (the device is checked to be
// little-endian).
std::vector<std::uint8_t> narrow_indices(const std::vector<std::uint32_t>& values, int bytes) {
  std::vector<std::uint8_t> packed(values.size() * std::size_t(bytes));
  for (std::size_t i = 0; i < values.size(); ++i)
    for (int b = 0; b < bytes; ++b) packed[i * bytes + b] = std::uint8_t(values[i] >> (8 * b));
  return packed;
}

template <typename T>
cl::Buffer upload(const cl::Context& context, const std::vector<T>& values,
                  std::uint64_t& total_bytes) {
  const std::size_t bytes = values.size() * sizeof(T);
  total_bytes += bytes;
  if (bytes == 0) return cl::Buffer(context, CL_MEM_READ_ONLY, sizeof(T));  // no empty buffers
  return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes,
                    const_cast<T*>(values.data()));
}

[[noreturn]] void rethrow_opencl(const cl::Error& error, const OpenClContext& context,
                                 const std::string& doing) {
  throw Error(doing + " on " + context.device().label() + ": " + error.what() + " failed with " +
              opencl_error_name(error.err()));
}

}  // namespace

double RelightTiming::kernel_seconds() const {
  double total = 0;
  for (const auto& timing : kernels) total += timing.seconds;
  return total;
}

std::uint64_t RelightTiming::kernel_bytes() const {
  std::uint64_t total = 0;
  for (const auto& timing : kernels) total += timing.bytes;
  return total;
}

std::uint64_t RelightTiming::kernel_flops() const {
  std::uint64_t total = 0;
  for (const auto& timing : kernels) total += timing.flops;
  return total;
}

const KernelTiming& RelightTiming::kernel(const std::string& name) const {
  for (const auto& timing : kernels)
    if (timing.kernel == name) return timing;
  throw Error("the last relighting call launched no '" + name + "' kernel");
}

OpenClRelighter::OpenClRelighter(OpenClContext& context, const CompressedField& field,
                                 const OpenClRelighterOptions& options)
    : context_(context), options_(options) {
  check_relightable(field);
  if (options.slice_rows < 0 || options.work_group_rows < 0 || options.head_entries < 0 ||
      options.max_batch < 1 || options.max_batch > max_batch_limit)
    throw Error("OpenCL relighter: slice rows " + std::to_string(options.slice_rows) +
                ", work-group rows " + std::to_string(options.work_group_rows) + ", head entries " +
                std::to_string(options.head_entries) + ", max batch " +
                std::to_string(options.max_batch) +
                " (expected slice rows, work-group rows and head entries >= 0 and a max batch "
                "of 1 to " +
                std::to_string(max_batch_limit) + ")");
  // Frames lie frame_stride_ floats apart in the output: a multiple of 1024 floats plus one cache
  // line, so that the frames' write streams fall into different cache sets (640x640x3 floats is
  // an exact multiple of 4 KiB, which would alias every frame onto the same set).
  frame_stride_ = (std::uint64_t(field.functions()) + 1023) / 1024 * 1024 + 16;
  if (frame_stride_ * std::uint64_t(options.max_batch) > 0xffffffffull)
    throw Error("OpenCL relighter: " + std::to_string(field.functions()) + " functions times " +
                std::to_string(options.max_batch) +
                " frames exceed the kernels' 32-bit output index; lower the batch size");
  shape_.width = field.width;
  shape_.height = field.height;
  shape_.channels = field.channels;
  shape_.lights = field.lights;
  shape_.terms = field.terms;
  shape_.clusters = field.clusters;
  shape_.transform = field.transform;
  rows_ = field.stored_rows();
  lights_even_ = field.lights + field.lights % 2;
  cluster_id_bytes_ = index_bytes(field.clusters);
  light_id_bytes_ = index_bytes(field.lights);
  const bool cpu = context.device().type == "cpu";
  work_group_rows_ = std::size_t(options.work_group_rows ? options.work_group_rows
                                 : cpu                   ? 1024
                                                         : 64);
  row_vector_ = options.row_vector ? options.row_vector : cpu ? 16 : 1;
  widest_row_ = int(field.residual.longest_row());
  // CPUs keep the first head_entries_ entries of each row in tall slices and the rest, if any row
  // is longer, in groups of one row vector (relight_layout.hpp); other devices keep every entry
  // in 32-row slices.
  head_entries_ =
      cpu ? std::uint32_t(options.head_entries ? options.head_entries : 24) : 0xffffffffu;
  tail_rows_ = cpu && std::uint32_t(widest_row_) > head_entries_ ? row_vector_ : 0;
  slice_rows_ = options.slice_rows ? options.slice_rows
                : cpu              ? tall_slice_rows(field, row_vector_, head_entries_)
                                   : 32;
  // A work-item's W on a CPU is then one contiguous run (a stream per term, a slice apart, was
  // half as fast at 48 terms); a warp's is one coalesced read per term on other devices.
  weight_rows_ = cpu ? std::min(16, slice_rows_) : slice_rows_;
  // The work ceiling's window: whole blocks of W, about 16 KB of them (at most 64 blocks).
  const int block_bytes = std::max(1, field.terms * int(sizeof(float)) * weight_rows_);
  int window_blocks = 1;
  while (window_blocks < 64 && 2 * window_blocks * block_bytes <= 16384) window_blocks *= 2;
  window_rows_ = weight_rows_ * window_blocks;
  if ((row_vector_ != 1 && row_vector_ != 4 && row_vector_ != 8 && row_vector_ != 16) ||
      slice_rows_ % row_vector_ != 0 || weight_rows_ % row_vector_ != 0 ||
      work_group_rows_ % row_vector_ != 0)
    throw Error("OpenCL relighter: row vector " + std::to_string(row_vector_) +
                " (expected 1, 4, 8 or 16, dividing the slice rows " + std::to_string(slice_rows_) +
                ", the rows of a block of W " + std::to_string(weight_rows_) +
                " and the work-group rows " + std::to_string(work_group_rows_) + ")");

  if (!context.device().device.getInfo<CL_DEVICE_ENDIAN_LITTLE>())
    throw Error("OpenCL relighter: " + context.device().label() +
                " is big-endian; the packed index arrays expect a little-endian device");

  check_relight_memory(field, 1);
  const RelightLayout layout =
      lay_out_field(field, {slice_rows_, weight_rows_, tail_rows_, head_entries_}, lights_even_);
  head_ = layout.head;
  tail_ = layout.tail;
  weight_bytes_ = layout.weights.bytes;
  residual_value_bytes_ = layout.residual_values.bytes;
  residual_scale_ = layout.residual_scale;
  products_scale_ = (field.quantization.weight_step > 0 ? field.quantization.weight_step : 1.0f) /
                    residual_scale_;
  stored_entries_ = layout.tail.offsets.back();
  nonzeros_ = field.residual.nonzeros();
  try {
    const cl::Context& cl_context = context.context();
    stored_function_ = upload(cl_context, layout.stored_function, device_bytes_);
    cluster_ = upload(cl_context, narrow_indices(layout.cluster, cluster_id_bytes_), device_bytes_);
    weights_ = upload(cl_context, layout.weights.data, device_bytes_);
    blocks_ = upload(cl_context, layout.blocks, device_bytes_);
    slice_offsets_ = upload(cl_context, layout.head.offsets, device_bytes_);
    tail_offsets_ = upload(cl_context, layout.tail.offsets, device_bytes_);
    residual_values_ = upload(cl_context, layout.residual_values.data, device_bytes_);
    residual_lights_ =
        upload(cl_context, narrow_indices(layout.residual_lights, light_id_bytes_), device_bytes_);
    // Dark pixels as runs of consecutive pixels, each at most dark_run_pixels long so that the
    // work-items' loops stay short.
    constexpr std::uint32_t dark_run_pixels = 256;
    std::vector<std::uint32_t> runs;
    for (std::size_t d = 0; d < field.dark_pixels.size(); ++d) {
      const std::uint32_t q = field.dark_pixels[d];
      if (!runs.empty() && runs[runs.size() - 3] + runs[runs.size() - 2] == q &&
          runs[runs.size() - 2] < dark_run_pixels)
        ++runs[runs.size() - 2];
      else
        runs.insert(runs.end(), {q, 1u, std::uint32_t(d)});
    }
    dark_run_count_ = runs.size() / 3;
    dark_pixel_count_ = field.dark_pixels.size();
    dark_ = field.dark;
    dark_runs_ = upload(cl_context, runs, device_bytes_);
    // A field without gains (an older container) relights every dark pixel with gain 1.
    dark_gains_ = upload(
        cl_context,
        field.dark_gains.empty()
            ? std::vector<float>(std::max<std::size_t>(1, dark_pixel_count_ * field.channels), 1.0f)
            : field.dark_gains,
        device_bytes_);
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context,
                   "uploading a compressed field of " + std::to_string(device_bytes_) + "+ bytes");
  }
  base_options_ =
      "-DTERMS=" + std::to_string(field.terms) + " -DCHANNELS=" + std::to_string(field.channels) +
      " -DSLICE_ROWS=" + std::to_string(slice_rows_) +
      " -DWEIGHT_ROWS=" + std::to_string(weight_rows_) +
      " -DTAIL_ROWS=" + std::to_string(tail_rows_) +
      " -DHEAD_ENTRIES=" + std::to_string(head_entries_) + "u" +
      " -DCLUSTER_T=" + index_type(cluster_id_bytes_) +
      " -DLIGHT_T=" + index_type(light_id_bytes_) + " -DROW_VECTOR=" + std::to_string(row_vector_) +
      " -DWEIGHT_T=" + layout.weights.type() + " -DRESIDUAL_T=" + layout.residual_values.type();
}

double OpenClRelighter::residual_padding() const {
  return stored_entries_ ? 1.0 - double(nonzeros_) / double(stored_entries_) : 0.0;
}

std::uint64_t OpenClRelighter::residual_bytes(int residual_cap) const {
  const std::uint32_t cap = std::uint32_t(residual_cap);
  const std::uint64_t slots =
      head_.slots_read(cap) +
      (reads_tail(residual_cap) ? tail_.slots_read(cap - head_entries_) : 0);
  return slots * std::uint64_t(residual_value_bytes_ + light_id_bytes_);
}

bool OpenClRelighter::reads_tail(int residual_cap) const {
  return tail_rows_ > 0 && std::uint32_t(residual_cap) > head_entries_;
}

OpenClRelighter::BatchProgram& OpenClRelighter::batch_program(int batch) {
  if (auto found = programs_.find(batch); found != programs_.end()) return found->second;
  BatchProgram program;
  program.batch = batch;
  const int width = batch_width(batch);
  program.batch_pad = (batch + width - 1) / width * width;
  const std::string options = base_options_ + " -DBATCH=" + std::to_string(batch) +
                              " -DBATCH_WIDTH=" + std::to_string(width);
  program.options = options;
  if (shape_.terms > 0) program.gemv = context_.kernel("relight.cl", "cluster_products", options);
  program.relight_rows = context_.kernel("relight.cl", "relight_rows", options);
  program.residual_rows = context_.kernel("relight.cl", "residual_rows", options);
  program.dark_pixels = context_.kernel("relight.cl", "dark_pixels", options);
  const cl::Context& cl_context = context_.context();
  program.dark = cl::Buffer(cl_context, CL_MEM_READ_ONLY,
                            std::size_t(shape_.channels) * program.batch_pad * sizeof(float));
  program.light = cl::Buffer(cl_context, CL_MEM_READ_ONLY, light_buffer_bytes(program));
  // A field without basis terms (residual only) still needs a valid buffer to bind.
  program.products = cl::Buffer(cl_context, CL_MEM_READ_WRITE,
                                std::max<std::uint64_t>(products_bytes(program), 4));
  const std::size_t output_bytes = std::size_t(batch) * frame_stride_ * sizeof(float);
  program.output = cl::Buffer(cl_context, CL_MEM_READ_WRITE, output_bytes);
  context_.queue().enqueueFillBuffer(program.output, 0.0f, 0, output_bytes);
  context_.queue().finish();
  return programs_.emplace(batch, std::move(program)).first->second;
}

std::uint64_t OpenClRelighter::light_buffer_bytes(const BatchProgram& program) const {
  return std::uint64_t(lights_even_) * shape_.channels * program.batch_pad * sizeof(float);
}

std::uint64_t OpenClRelighter::products_bytes(const BatchProgram& program) const {
  return std::uint64_t(shape_.clusters) * shape_.terms * shape_.channels * program.batch_pad *
         sizeof(float);
}

void OpenClRelighter::upload_lights(BatchProgram& program,
                                    const std::vector<const LightRgb*>& lights, Pass pass) {
  const int channels = shape_.channels;
  std::vector<float>& packed = program.staging;  // read by the write below until run_pass ends
  packed.assign(std::size_t(lights_even_) * channels * program.batch_pad, 0.0f);
  for (std::size_t b = 0; b < lights.size(); ++b) {
    const RowMatrixF basis_light = light_in_field_basis(shape_, *lights[b]);
    for (int i = 0; i < shape_.lights; ++i)
      for (int c = 0; c < channels; ++c)
        packed[(std::size_t(i) * channels + c) * program.batch_pad + b] =
            basis_light(i, c) * residual_scale_;
  }
  context_.queue().enqueueWriteBuffer(program.light, CL_FALSE, 0, packed.size() * sizeof(float),
                                      packed.data());
  if (dark_pixel_count_ == 0) return;
  // Each frame's dark-model value per channel, dark[c] . I, computed here (lights x channels);
  // zero for the residual term alone (the dark model is not residual).
  std::vector<float>& dark = program.dark_staging;
  dark.assign(std::size_t(channels) * program.batch_pad, 0.0f);
  for (std::size_t b = 0; pass == Pass::relight && b < lights.size(); ++b) {
    const RowMatrixF basis_light = light_in_field_basis(shape_, *lights[b]);
    for (int c = 0; c < channels; ++c) {
      double sum = 0;
      for (int i = 0; i < shape_.lights; ++i)
        sum += double(dark_[std::size_t(c) * shape_.lights + i]) * basis_light(i, c);
      dark[std::size_t(c) * program.batch_pad + b] = float(sum);
    }
  }
  context_.queue().enqueueWriteBuffer(program.dark, CL_FALSE, 0, dark.size() * sizeof(float),
                                      dark.data());
}

OpenClRelighter::Launch OpenClRelighter::launch_dark(BatchProgram& program) {
  cl::Kernel& kernel = program.dark_pixels;
  kernel.setArg(0, cl_uint(dark_run_count_));
  kernel.setArg(1, cl_uint(frame_stride_));
  kernel.setArg(2, dark_runs_);
  kernel.setArg(3, program.dark);
  kernel.setArg(4, dark_gains_);
  kernel.setArg(5, program.output);
  cl::Event event;
  context_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dark_run_count_),
                                        cl::NullRange, nullptr, &event);
  KernelTiming timing{"dark", 0, 0};
  timing.bytes = dark_run_count_ * 12 + std::uint64_t(shape_.channels) * program.batch_pad * 4 +
                 dark_pixel_count_ * shape_.channels * sizeof(float) +
                 dark_pixel_count_ * shape_.channels * std::uint64_t(program.batch) * sizeof(float);
  timing.flops = dark_pixel_count_ * shape_.channels * std::uint64_t(program.batch);
  return {timing, event};
}

OpenClRelighter::Launch OpenClRelighter::launch_gemv(BatchProgram& program) {
  const int term_pairs = (shape_.terms + 1) / 2;
  const int vectors = program.batch_pad / batch_width(program.batch);
  cl::Kernel& kernel = program.gemv;
  kernel.setArg(0, cl_uint(lights_even_ / 2));
  kernel.setArg(1, blocks_);
  kernel.setArg(2, program.light);
  kernel.setArg(3, program.products);
  cl::Event event;
  context_.queue().enqueueNDRangeKernel(
      kernel, cl::NullRange, cl::NDRange(std::size_t(shape_.clusters) * term_pairs * vectors),
      cl::NullRange, nullptr, &event);
  KernelTiming timing{"gemv", 0, 0};
  timing.bytes = std::uint64_t(shape_.clusters) * term_pairs * (lights_even_ / 2) * 16 +
                 light_buffer_bytes(program) + products_bytes(program);
  timing.flops = 2 * std::uint64_t(shape_.clusters) * (2 * term_pairs) * lights_even_ *
                 shape_.channels * std::uint64_t(program.batch_pad);
  return {timing, event};
}

OpenClRelighter::Launch OpenClRelighter::launch_rows(BatchProgram& program, Pass pass,
                                                     int residual_cap) {
  const bool with_basis = pass != Pass::residual;
  cl::Kernel& kernel = pass == Pass::ceiling ? program.ceiling_rows
                       : with_basis          ? program.relight_rows
                                             : program.residual_rows;
  int arg = 0;
  kernel.setArg(arg++, cl_uint(rows_));
  kernel.setArg(arg++, cl_uint(frame_stride_));
  kernel.setArg(arg++, cl_uint(residual_cap));
  kernel.setArg(arg++, stored_function_);
  if (with_basis) {
    kernel.setArg(arg++, cluster_);
    kernel.setArg(arg++, weights_);
    kernel.setArg(arg++, program.products);
  }
  kernel.setArg(arg++, slice_offsets_);
  kernel.setArg(arg++, tail_offsets_);
  kernel.setArg(arg++, residual_values_);
  kernel.setArg(arg++, residual_lights_);
  kernel.setArg(arg++, program.light);
  kernel.setArg(arg++, program.output);
  // Single-frame passes relight row_vector_ rows per work-item.
  const std::size_t rows_per_item = program.batch == 1 ? std::size_t(row_vector_) : 1;
  const std::size_t local = work_group_rows_ / rows_per_item;
  const std::size_t items = (rows_ + rows_per_item - 1) / rows_per_item;
  cl::Event event;
  context_.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                        cl::NDRange((items + local - 1) / local * local),
                                        cl::NDRange(local), nullptr, &event);
  KernelTiming timing{pass == Pass::ceiling ? "ceiling" : with_basis ? "rows" : "spmv", 0, 0};
  // Per row: its function index, its output per frame; with the basis also its cluster id and
  // weights. Shared by all rows: the group offsets, the light vectors and the products (cached).
  std::uint64_t per_row = sizeof(std::uint32_t) + std::uint64_t(program.batch) * sizeof(float);
  if (with_basis) per_row += cluster_id_bytes_ + std::uint64_t(shape_.terms) * weight_bytes_;
  timing.bytes = rows_ * per_row + residual_bytes(residual_cap) +
                 (head_.offsets.size() + (reads_tail(residual_cap) ? tail_.offsets.size() : 0)) *
                     sizeof(std::uint32_t) +
                 light_buffer_bytes(program) + (with_basis ? products_bytes(program) : 0);
  // A multiply-add per weight and per residual slot read (padding too), for every frame.
  const std::uint64_t slots =
      residual_bytes(residual_cap) / std::uint64_t(residual_value_bytes_ + light_id_bytes_);
  timing.flops = 2 * std::uint64_t(program.batch) *
                 ((with_basis ? rows_ * std::uint64_t(shape_.terms) : 0) + slots);
  return {timing, event};
}

void OpenClRelighter::run_pass(const std::vector<const LightRgb*>& lights, int residual_cap,
                               Pass pass, Image* images) {
  BatchProgram& program = batch_program(int(lights.size()));
  // Everything is enqueued without waiting (the queue is in order) and finished once at the end;
  // on failure the queue is drained before the error leaves, so nothing writes into `images` later.
  try {
    upload_lights(program, lights, pass);
    std::vector<Launch> launches;
    const bool has_basis = shape_.terms > 0 && shape_.clusters > 0;
    if (has_basis && pass != Pass::residual) launches.push_back(launch_gemv(program));
    if (pass != Pass::products && rows_ > 0)
      launches.push_back(launch_rows(program, pass, residual_cap));
    if (pass != Pass::products && dark_run_count_ > 0) launches.push_back(launch_dark(program));
    const std::size_t functions = std::size_t(shape_.functions());
    for (std::size_t b = 0; pass != Pass::products && b < lights.size(); ++b) {
      Image& image = images[b];
      if (image.width != shape_.width || image.height != shape_.height ||
          image.channels != shape_.channels || image.pixels.size() != functions)
        image = Image(shape_.width, shape_.height, shape_.channels);
      context_.queue().enqueueReadBuffer(program.output, CL_FALSE,
                                         b * frame_stride_ * sizeof(float),
                                         functions * sizeof(float), image.pixels.data());
    }
    context_.queue().finish();
    for (auto& launch : launches) {
      launch.timing.seconds = event_seconds(launch.event);
      last_timing_.kernels.push_back(launch.timing);
    }
  } catch (...) {
    try {
      context_.queue().finish();
    } catch (const cl::Error&) {
      // The original error is the one to report.
    }
    throw;
  }
}

void OpenClRelighter::relight_batch_into(const std::vector<LightRgb>& lights, int residual_cap,
                                         std::vector<Image>& images) {
  check_residual_cap(residual_cap);
  const auto start = std::chrono::steady_clock::now();
  last_timing_ = RelightTiming{};
  last_timing_.frames = int(lights.size());
  images.resize(lights.size());
  try {
    for (std::size_t first = 0; first < lights.size(); first += std::size_t(options_.max_batch)) {
      std::vector<const LightRgb*> pass;
      for (std::size_t b = first; b < std::min(lights.size(), first + options_.max_batch); ++b)
        pass.push_back(&lights[b]);
      run_pass(pass, residual_cap, Pass::relight, images.data() + first);
    }
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context_, "relighting " + std::to_string(lights.size()) + " frames");
  }
  last_timing_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double OpenClRelighter::work_ceiling_seconds(int frames, int residual_cap) {
  check_residual_cap(residual_cap);
  if (frames < 1)
    throw Error("OpenCL relighter: the work ceiling of " + std::to_string(frames) +
                " frames (expected at least 1)");
  if (rows_ == 0) return 0;
  // In passes of at most max_batch frames, as relight_batch_into relights them.
  double seconds = 0;
  for (int first = 0; first < frames; first += options_.max_batch)
    seconds +=
        work_ceiling_pass_seconds(std::min(options_.max_batch, frames - first), residual_cap);
  return seconds;
}

double OpenClRelighter::work_ceiling_pass_seconds(int frames, int residual_cap) {
  try {
    BatchProgram& program = batch_program(frames);
    if (!program.ceiling_rows())
      program.ceiling_rows = context_.kernel(
          "relight.cl", "relight_rows",
          program.options + " -DWORK_CEILING -DWINDOW_ROWS=" + std::to_string(window_rows_));
    // Zeros, not NaN from an earlier pass's garbage: the kernel then writes nothing. The next
    // relighting uploads its lights and computes its products anew.
    cl::CommandQueue& queue = context_.queue();
    queue.enqueueFillBuffer(program.light, 0.0f, 0, light_buffer_bytes(program));
    queue.enqueueFillBuffer(program.products, 0.0f, 0,
                            std::max<std::uint64_t>(products_bytes(program), 4));
    Launch launch = launch_rows(program, Pass::ceiling, residual_cap);
    queue.finish();
    return event_seconds(launch.event);
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context_,
                   "timing the work ceiling of " + std::to_string(frames) + " frames");
  }
}

std::vector<Image> OpenClRelighter::relight_batch(const std::vector<LightRgb>& lights,
                                                  int residual_cap) {
  std::vector<Image> images;
  relight_batch_into(lights, residual_cap, images);
  return images;
}

Image OpenClRelighter::relight(const LightRgb& light, int residual_cap) {
  return std::move(relight_batch({light}, residual_cap).front());
}

void OpenClRelighter::relight_residual_into(const LightRgb& light, int residual_cap, Image& image) {
  check_residual_cap(residual_cap);
  const auto start = std::chrono::steady_clock::now();
  last_timing_ = RelightTiming{};
  last_timing_.frames = 1;
  try {
    run_pass({&light}, residual_cap, Pass::residual, &image);
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context_, "computing the residual image");
  }
  last_timing_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Image OpenClRelighter::relight_residual(const LightRgb& light, int residual_cap) {
  Image image;
  relight_residual_into(light, residual_cap, image);
  return image;
}

std::vector<float> OpenClRelighter::cluster_products(const LightRgb& light) {
  const auto start = std::chrono::steady_clock::now();
  last_timing_ = RelightTiming{};
  last_timing_.frames = 1;
  try {
    run_pass({&light}, 0, Pass::products, nullptr);
    BatchProgram& program = batch_program(1);
    std::vector<float> products(products_bytes(program) / sizeof(float));
    if (!products.empty())
      context_.queue().enqueueReadBuffer(program.products, CL_TRUE, 0,
                                         products.size() * sizeof(float), products.data());
    // The device's products carry the layout's step factors (relight_layout.hpp): undo them.
    for (float& v : products) v /= products_scale_ * residual_scale_;
    last_timing_.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return products;
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context_, "computing the cluster products");
  }
}

}  // namespace relume
