// Implementation of the JPEG 2000 plane coding (see jpeg2000_planes.hpp) over OpenJPEG's stream
// interface, reading and writing memory.
#include "container/jpeg2000_planes.hpp"

#include <openjpeg.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <relume/error.hpp>
#include <thread>

namespace relume {
namespace {

constexpr int plane_precision = 16;
// Resolution levels of the wavelet (five decompositions), fewer for small planes.
constexpr int max_resolution_levels = 6;

struct CodecDeleter {
  void operator()(opj_codec_t* codec) const { opj_destroy_codec(codec); }
};
struct StreamDeleter {
  void operator()(opj_stream_t* stream) const { opj_stream_destroy(stream); }
};
struct ImageDeleter {
  void operator()(opj_image_t* image) const { opj_image_destroy(image); }
};
using Codec = std::unique_ptr<opj_codec_t, CodecDeleter>;
using Stream = std::unique_ptr<opj_stream_t, StreamDeleter>;
using Image = std::unique_ptr<opj_image_t, ImageDeleter>;

// OpenJPEG's error messages, kept for the Error it leads to.
void keep_message(const char* message, void* client) {
  auto& messages = *static_cast<std::string*>(client);
  if (!messages.empty()) messages += "; ";
  messages += message;
  while (!messages.empty() && (messages.back() == '\n' || messages.back() == ' '))
    messages.pop_back();
}
void ignore_message(const char*, void*) {}

void set_handlers(opj_codec_t* codec, std::string& errors) {
  opj_set_error_handler(codec, keep_message, &errors);
  opj_set_warning_handler(codec, ignore_message, nullptr);
  opj_set_info_handler(codec, ignore_message, nullptr);
}

OPJ_UINT32 thread_count(unsigned threads) {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

// A growing byte buffer OpenJPEG writes into (it seeks back to patch markers).
struct MemoryOutput {
  std::vector<std::uint8_t> bytes;
  std::size_t position = 0;
};

OPJ_SIZE_T write_memory(void* data, OPJ_SIZE_T size, void* user) {
  auto& out = *static_cast<MemoryOutput*>(user);
  if (out.position + size > out.bytes.size()) out.bytes.resize(out.position + size);
  std::memcpy(out.bytes.data() + out.position, data, size);
  out.position += size;
  return size;
}
OPJ_OFF_T skip_output(OPJ_OFF_T size, void* user) {
  auto& out = *static_cast<MemoryOutput*>(user);
  if (size < 0 && OPJ_OFF_T(out.position) < -size) return -1;
  out.position = std::size_t(OPJ_OFF_T(out.position) + size);
  if (out.position > out.bytes.size()) out.bytes.resize(out.position);
  return size;
}
OPJ_BOOL seek_output(OPJ_OFF_T position, void* user) {
  auto& out = *static_cast<MemoryOutput*>(user);
  if (position < 0) return OPJ_FALSE;
  out.position = std::size_t(position);
  if (out.position > out.bytes.size()) out.bytes.resize(out.position);
  return OPJ_TRUE;
}

struct MemoryInput {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::size_t position = 0;
};

OPJ_SIZE_T read_memory(void* buffer, OPJ_SIZE_T size, void* user) {
  auto& in = *static_cast<MemoryInput*>(user);
  if (in.position >= in.size) return OPJ_SIZE_T(-1);
  const std::size_t n = std::min<std::size_t>(size, in.size - in.position);
  std::memcpy(buffer, in.data + in.position, n);
  in.position += n;
  return n;
}
OPJ_OFF_T skip_input(OPJ_OFF_T size, void* user) {
  auto& in = *static_cast<MemoryInput*>(user);
  const OPJ_OFF_T to = std::clamp<OPJ_OFF_T>(OPJ_OFF_T(in.position) + size, 0, OPJ_OFF_T(in.size));
  const OPJ_OFF_T moved = to - OPJ_OFF_T(in.position);
  in.position = std::size_t(to);
  return moved;
}
OPJ_BOOL seek_input(OPJ_OFF_T position, void* user) {
  auto& in = *static_cast<MemoryInput*>(user);
  if (position < 0 || std::uint64_t(position) > in.size) return OPJ_FALSE;
  in.position = std::size_t(position);
  return OPJ_TRUE;
}

int resolution_levels(int width, int height) {
  int levels = 1;
  while (levels < max_resolution_levels && (std::min(width, height) >> levels) >= 8) ++levels;
  return levels;
}

Image planes_image(const IntegerPlanes& planes) {
  std::vector<opj_image_cmptparm_t> components(std::size_t(planes.count));
  for (opj_image_cmptparm_t& component : components) {
    std::memset(&component, 0, sizeof component);
    component.dx = component.dy = 1;
    component.w = OPJ_UINT32(planes.width);
    component.h = OPJ_UINT32(planes.height);
    component.prec = plane_precision;
    component.sgnd = 1;
  }
  Image image(
      opj_image_create(OPJ_UINT32(planes.count), components.data(), OPJ_CLRSPC_UNSPECIFIED));
  if (!image) throw Error("JPEG 2000: cannot allocate the image of the planes");
  image->x0 = image->y0 = 0;
  image->x1 = OPJ_UINT32(planes.width);
  image->y1 = OPJ_UINT32(planes.height);
  const std::size_t area = std::size_t(planes.width) * std::size_t(planes.height);
  for (int c = 0; c < planes.count; ++c)
    std::copy_n(planes.samples.data() + std::size_t(c) * area, area, image->comps[c].data);
  return image;
}

// One encode at compression ratio `ratio` (raw 16-bit bytes over coded bytes). The image is made
// anew for each: with a single tile OpenJPEG takes over the image's sample buffers.
std::vector<std::uint8_t> encode_at_ratio(const IntegerPlanes& planes, double ratio,
                                          unsigned threads) {
  const Image image = planes_image(planes);
  opj_cparameters_t parameters;
  opj_set_default_encoder_parameters(&parameters);
  parameters.tcp_numlayers = 1;
  parameters.tcp_rates[0] = float(ratio);
  parameters.cp_disto_alloc = 1;
  parameters.irreversible = 1;
  parameters.tcp_mct = 0;
  parameters.numresolution = resolution_levels(planes.width, planes.height);
  std::string errors;
  Codec codec(opj_create_compress(OPJ_CODEC_J2K));
  if (!codec) throw Error("JPEG 2000: cannot create the encoder");
  set_handlers(codec.get(), errors);
  if (!opj_setup_encoder(codec.get(), &parameters, image.get()))
    throw Error("JPEG 2000: cannot set up the encoder: " + errors);
  opj_codec_set_threads(codec.get(), int(thread_count(threads)));
  MemoryOutput out;
  Stream stream(opj_stream_create(OPJ_J2K_STREAM_CHUNK_SIZE, OPJ_FALSE));
  if (!stream) throw Error("JPEG 2000: cannot create the output stream");
  opj_stream_set_user_data(stream.get(), &out, nullptr);
  opj_stream_set_write_function(stream.get(), write_memory);
  opj_stream_set_skip_function(stream.get(), skip_output);
  opj_stream_set_seek_function(stream.get(), seek_output);
  if (!opj_start_compress(codec.get(), image.get(), stream.get()) ||
      !opj_encode(codec.get(), stream.get()) || !opj_end_compress(codec.get(), stream.get()))
    throw Error("JPEG 2000: encoding the planes failed: " + errors);
  stream.reset();
  out.bytes.resize(out.position);
  return std::move(out.bytes);
}

}  // namespace

std::vector<std::uint8_t> encode_jpeg2000_planes(const IntegerPlanes& planes,
                                                 std::uint64_t max_bytes, unsigned threads) {
  const std::size_t area = std::size_t(planes.width) * std::size_t(planes.height);
  if (planes.width < 1 || planes.height < 1 || planes.count < 1 ||
      planes.samples.size() != area * std::size_t(planes.count))
    throw Error("JPEG 2000: " + std::to_string(planes.count) + " planes of " +
                std::to_string(planes.width) + "x" + std::to_string(planes.height) +
                " do not match their " + std::to_string(planes.samples.size()) + " samples");
  const double raw_bytes = double(area) * planes.count * (plane_precision / 8);
  // The rate allocation aims at the ratio's bytes less the headers and lands near, not on, them:
  // the ratio is searched for, in its logarithm, between the ratios known to fit and to overshoot
  // (interpolating by the sizes they gave), keeping the largest codestream that fits; without a
  // fit, the smallest codestream made.
  const double goal = 0.995 * double(max_bytes);
  std::vector<std::uint8_t> best, smallest;
  double ratio = std::max(1.0, raw_bytes / std::max(goal, 1.0));
  double fit_ratio = 0, fit_size = 0, over_ratio = 0, over_size = 0;  // 0: not known yet
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::vector<std::uint8_t> coded = encode_at_ratio(planes, ratio, threads);
    const double size = double(coded.size());
    const bool fits = size <= double(max_bytes);
    if (fits) {
      fit_ratio = ratio;
      fit_size = size;
      if (coded.size() > best.size()) best = std::move(coded);
      if (size >= 0.99 * double(max_bytes) || ratio <= 1.0) break;
    } else {
      // A codestream that cannot get smaller: its headers and the least the planes take.
      if (!smallest.empty() && size >= double(smallest.size()) && ratio > over_ratio) break;
      if (smallest.empty() || coded.size() < smallest.size()) smallest = std::move(coded);
      over_ratio = ratio;
      over_size = size;
    }
    if (fit_ratio > 0 && over_ratio > 0) {
      const double t = std::log(goal / over_size) / std::log(fit_size / over_size);
      ratio = over_ratio * std::pow(fit_ratio / over_ratio, std::clamp(t, 0.1, 0.9));
    } else {
      ratio = std::max(1.0, ratio * size / goal);
    }
  }
  return best.empty() ? smallest : best;
}

IntegerPlanes decode_jpeg2000_planes(const std::uint8_t* data, std::size_t size, int width,
                                     int height, int count, unsigned threads,
                                     const std::string& where) {
  std::string errors;
  Codec codec(opj_create_decompress(OPJ_CODEC_J2K));
  if (!codec) throw Error(where + ": cannot create the JPEG 2000 decoder");
  set_handlers(codec.get(), errors);
  opj_dparameters_t parameters;
  opj_set_default_decoder_parameters(&parameters);
  if (!opj_setup_decoder(codec.get(), &parameters))
    throw Error(where + ": cannot set up the JPEG 2000 decoder: " + errors);
  opj_decoder_set_strict_mode(codec.get(), OPJ_TRUE);
  opj_codec_set_threads(codec.get(), int(thread_count(threads)));
  MemoryInput in{data, size, 0};
  Stream stream(opj_stream_create(OPJ_J2K_STREAM_CHUNK_SIZE, OPJ_TRUE));
  if (!stream) throw Error(where + ": cannot create the JPEG 2000 input stream");
  opj_stream_set_user_data(stream.get(), &in, nullptr);
  opj_stream_set_user_data_length(stream.get(), size);
  opj_stream_set_read_function(stream.get(), read_memory);
  opj_stream_set_skip_function(stream.get(), skip_input);
  opj_stream_set_seek_function(stream.get(), seek_input);
  opj_image_t* header_image = nullptr;
  if (!opj_read_header(stream.get(), codec.get(), &header_image))
    throw Error(where + ": not a JPEG 2000 codestream" + (errors.empty() ? "" : ": " + errors));
  const Image image(header_image);
  const std::string expected = std::to_string(count) + " signed 16-bit planes of " +
                               std::to_string(width) + "x" + std::to_string(height);
  if (image->x0 != 0 || image->y0 != 0 || image->x1 != OPJ_UINT32(width) ||
      image->y1 != OPJ_UINT32(height) || image->numcomps != OPJ_UINT32(count))
    throw Error(where + ": the codestream holds " + std::to_string(image->numcomps) +
                " planes of " + std::to_string(image->x1 - image->x0) + "x" +
                std::to_string(image->y1 - image->y0) + ", expected " + expected);
  for (OPJ_UINT32 c = 0; c < image->numcomps; ++c) {
    const opj_image_comp_t& component = image->comps[c];
    if (component.dx != 1 || component.dy != 1 || component.prec != plane_precision ||
        !component.sgnd)
      throw Error(where + ": plane " + std::to_string(c) + " is " +
                  (component.sgnd ? "signed " : "unsigned ") + std::to_string(component.prec) +
                  "-bit with sub-sampling " + std::to_string(component.dx) + "x" +
                  std::to_string(component.dy) + ", expected " + expected);
  }
  if (!opj_decode(codec.get(), stream.get(), image.get()) ||
      !opj_end_decompress(codec.get(), stream.get()))
    throw Error(where + ": the JPEG 2000 codestream does not decode" +
                (errors.empty() ? "" : ": " + errors));
  IntegerPlanes planes{width, height, count, {}};
  const std::size_t area = std::size_t(width) * std::size_t(height);
  planes.samples.resize(area * std::size_t(count));
  for (int c = 0; c < count; ++c) {
    const opj_image_comp_t& component = image->comps[c];
    if (!component.data || component.w != OPJ_UINT32(width) || component.h != OPJ_UINT32(height))
      throw Error(where + ": plane " + std::to_string(c) + " did not decode whole");
    std::copy_n(component.data, area, planes.samples.data() + std::size_t(c) * area);
  }
  return planes;
}

}  // namespace relume
