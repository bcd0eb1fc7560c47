// Encoding relit frames with FFmpeg's libraries (the 5.x API: send_frame / receive_packet).
#include "commands/relight/video_writer.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <vector>

#include "core/console.hpp"
#include "image/srgb_codes.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

std::string ffmpeg_error(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

// The first encoder of the preference list for this container that FFmpeg has.
const AVCodec* find_encoder(const AVOutputFormat* format, const std::string& requested,
                            const fs::path& path) {
  if (!requested.empty()) {
    const AVCodec* codec = avcodec_find_encoder_by_name(requested.c_str());
    if (!codec || codec->type != AVMEDIA_TYPE_VIDEO)
      throw Error("FFmpeg has no video encoder '" + requested + "' (for " + path.string() + ")");
    return codec;
  }
  const bool webm = std::string(format->name).find("webm") != std::string::npos;
  const std::vector<const char*> preferred = webm ? std::vector<const char*>{"libvpx-vp9", "libvpx"}
                                                  : std::vector<const char*>{"libx264", "mpeg4"};
  for (const char* name : preferred)
    if (const AVCodec* codec = avcodec_find_encoder_by_name(name)) return codec;
  throw Error("this FFmpeg has none of the encoders " + std::string(preferred[0]) + ", " +
              preferred[1] + " for " + path.string() + " (name one with --codec)");
}

const AVOutputFormat* find_container(const fs::path& path) {
  const AVOutputFormat* container = av_guess_format(nullptr, path.c_str(), nullptr);
  if (!container)
    throw Error("FFmpeg knows no video container for " + path.string() +
                " (use .mp4, .mkv, .mov or .webm)");
  return container;
}

void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0 || ::fsync(fd) != 0) {
    if (fd >= 0) ::close(fd);
    throw Error("cannot sync " + path.string());
  }
  ::close(fd);
}

}  // namespace

struct VideoWriter::State {
  fs::path path, temp;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  SwsContext* scale = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  int width = 0, height = 0;  // encoded (even)
  int frames = 0;
  bool finished = false;
  std::vector<std::uint8_t> rgb;  // one frame, 8-bit sRGB

  ~State() {
    av_packet_free(&packet);
    av_frame_free(&frame);
    sws_freeContext(scale);
    avcodec_free_context(&codec);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    std::error_code ignored;
    if (!finished) fs::remove(temp, ignored);
  }

  void check(int code, const std::string& what) const {
    if (code < 0)
      throw Error("cannot write video " + path.string() + ": " + what + ": " + ffmpeg_error(code));
  }

  // Sends `input` (nullptr: flush) and writes every packet the encoder gives back.
  void encode(const AVFrame* input) {
    check(avcodec_send_frame(codec, input), "encoding");
    for (;;) {
      const int received = avcodec_receive_packet(codec, packet);
      if (received == AVERROR(EAGAIN) || received == AVERROR_EOF) return;
      check(received, "encoding");
      if (packet->duration == 0) packet->duration = 1;  // one frame, so the last one shows too
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      check(av_interleaved_write_frame(format, packet), "writing");
    }
  }
};

VideoWriter::VideoWriter(const fs::path& path, int width, int height, int frames_per_second,
                         const std::string& codec_name)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  std::string temp_name = path.filename().string();
  temp_name.insert(temp_name.begin(), '.');
  temp_name += ".relume-partial";
  s.temp = path.parent_path() / temp_name;
  s.width = width & ~1;
  s.height = height & ~1;
  if (s.width < 2 || s.height < 2)
    throw Error("video " + path.string() + ": frames of " + std::to_string(width) + "x" +
                std::to_string(height) + " are too small");
  // 4:2:0 chroma needs even sizes: an odd last row or column was left out without a word.
  if (s.width != width || s.height != height)
    note("video %s: frames of %dx%d are encoded as %dx%d (its chroma needs even sizes): the last "
         "%s left out; the image frames keep it",
         path.string().c_str(), width, height, s.width, s.height,
         s.width != width && s.height != height ? "row and column are"
         : s.height != height                   ? "row is"
                                                : "column is");
  if (frames_per_second < 1 || frames_per_second > 240)
    throw Error("video frame rate must be 1 to 240, got " + std::to_string(frames_per_second));
  // FFmpeg's own messages (libx264's statistics) only when verbose; errors come back as codes.
  av_log_set_level(verbosity() == Verbosity::verbose ? AV_LOG_INFO : AV_LOG_ERROR);
  const AVOutputFormat* container = find_container(path);
  const AVCodec* encoder = find_encoder(container, codec_name, path);

  s.check(avformat_alloc_output_context2(&s.format, container, nullptr, s.temp.c_str()),
          "container");
  s.stream = avformat_new_stream(s.format, nullptr);
  s.codec = avcodec_alloc_context3(encoder);
  s.frame = av_frame_alloc();
  s.packet = av_packet_alloc();
  if (!s.stream || !s.codec || !s.frame || !s.packet) throw Error("out of memory for video");
  s.codec->width = s.width;
  s.codec->height = s.height;
  s.codec->time_base = {1, frames_per_second};
  s.codec->framerate = {frames_per_second, 1};
  s.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  s.codec->color_range = AVCOL_RANGE_MPEG;
  s.codec->colorspace = AVCOL_SPC_SMPTE170M;    // the BT.601 matrix swscale applies
  s.codec->color_primaries = AVCOL_PRI_BT709;   // sRGB's primaries
  s.codec->color_trc = AVCOL_TRC_IEC61966_2_1;  // the sRGB curve the frames carry
  if (s.format->oformat->flags & AVFMT_GLOBALHEADER) s.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* settings = nullptr;
  if (std::string(encoder->name) == "libx264") av_dict_set(&settings, "crf", "18", 0);
  if (std::string(encoder->name).rfind("libvpx", 0) == 0) {
    av_dict_set(&settings, "crf", "20", 0);
    s.codec->bit_rate = 0;  // constant quality
  }
  if (std::string(encoder->name) == "mpeg4") {
    s.codec->flags |= AV_CODEC_FLAG_QSCALE;
    s.codec->global_quality = FF_QP2LAMBDA * 3;
  }
  const int opened = avcodec_open2(s.codec, encoder, &settings);
  av_dict_free(&settings);
  s.check(opened, std::string("opening the ") + encoder->name + " encoder");
  s.check(avcodec_parameters_from_context(s.stream->codecpar, s.codec), "stream parameters");
  s.stream->time_base = s.codec->time_base;
  s.stream->avg_frame_rate = s.codec->framerate;

  s.frame->format = s.codec->pix_fmt;
  s.frame->width = s.width;
  s.frame->height = s.height;
  s.check(av_frame_get_buffer(s.frame, 0), "frame buffer");
  s.scale = sws_getContext(s.width, s.height, AV_PIX_FMT_RGB24, s.width, s.height,
                           AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!s.scale) throw Error("video " + path.string() + ": no RGB to YUV conversion");
  s.rgb.resize(std::size_t(s.width) * s.height * 3);

  s.check(avio_open(&s.format->pb, s.temp.c_str(), AVIO_FLAG_WRITE), "opening the file");
  s.check(avformat_write_header(s.format, nullptr), "header");
}

VideoWriter::~VideoWriter() = default;

void VideoWriter::check_target(const fs::path& path, const std::string& codec) {
  find_encoder(find_container(path), codec, path);
}

void VideoWriter::add_frame(const Image& image, double exposure) {
  State& s = *state_;
  if (image.width < s.width || image.height < s.height)
    throw Error("video " + s.path.string() + ": frame of " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " in a video of " + std::to_string(s.width) + "x" +
                std::to_string(s.height));
  const float scale = static_cast<float>(std::exp2(exposure));
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float linear = image.at(x, y, image.channels >= 3 ? c : 0) * scale;
        const float encoded = linear_to_srgb(unit_clamped(linear));
        s.rgb[(std::size_t(y) * s.width + x) * 3 + c] =
            static_cast<std::uint8_t>(std::lround(encoded * 255.0f));
      }
  s.check(av_frame_make_writable(s.frame), "frame buffer");
  const std::uint8_t* source[1] = {s.rgb.data()};
  const int stride[1] = {3 * s.width};
  sws_scale(s.scale, source, stride, 0, s.height, s.frame->data, s.frame->linesize);
  s.frame->pts = s.frames++;
  s.encode(s.frame);
}

void VideoWriter::finish() {
  State& s = *state_;
  s.encode(nullptr);
  s.check(av_write_trailer(s.format), "trailer");
  s.check(avio_closep(&s.format->pb), "closing the file");
  sync_file(s.temp);
  fs::rename(s.temp, s.path);
  s.finished = true;
}

std::string VideoWriter::codec_name() const { return state_->codec->codec->name; }
int VideoWriter::frames() const { return state_->frames; }

}  // namespace relume
