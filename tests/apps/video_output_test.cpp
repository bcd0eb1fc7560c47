// Tests of relight-sequence --video: the video is decoded here with FFmpeg's libraries, as a
// player does (demux, decode with the flush at the end, YUV to RGB), and every frame is the
// picture the PNG frames of the same run hold, up to the codec's loss; the default H.264 and
// MPEG-4 part 2 in Matroska; an odd frame size noted; refused targets; no half-written file after
// a failure.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

// Every frame of a video as 8-bit RGB, with its size, and the codec's name.
struct DecodedVideo {
  int width = 0, height = 0;
  std::string codec;
  std::vector<std::vector<std::uint8_t>> frames;
};

DecodedVideo decode(const std::string& path) {
  DecodedVideo video;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) return video;
  avformat_find_stream_info(format, nullptr);
  const AVCodec* decoder = nullptr;
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  AVCodecContext* codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(codec, format->streams[stream]->codecpar);
  avcodec_open2(codec, decoder, nullptr);
  video.width = codec->width, video.height = codec->height, video.codec = decoder->name;
  SwsContext* scale =
      sws_getContext(codec->width, codec->height, codec->pix_fmt, codec->width, codec->height,
                     AV_PIX_FMT_RGB24, SWS_BICUBIC, nullptr, nullptr, nullptr);
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const auto receive = [&] {
    while (avcodec_receive_frame(codec, frame) == 0) {
      std::vector<std::uint8_t> rgb(std::size_t(video.width) * video.height * 3);
      std::uint8_t* out[1] = {rgb.data()};
      const int stride[1] = {3 * video.width};
      sws_scale(scale, frame->data, frame->linesize, 0, video.height, out, stride);
      video.frames.push_back(std::move(rgb));
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == stream) {
      avcodec_send_packet(codec, packet);
      receive();
    }
    av_packet_unref(packet);
  }
  avcodec_send_packet(codec, nullptr);  // flush: the frames the decoder still holds
  receive();
  av_frame_free(&frame);
  av_packet_free(&packet);
  sws_freeContext(scale);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  return video;
}

class VideoOutput : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    run_or_fail("synth -o '" + path("scene") + "' --size 64x48 --lights 30 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
                "' --clusters 3 --terms 2 --residual 3");
    run_or_fail(sequence() + "-o '" + path("png/%d.png") + "'");
  }
  static std::string sequence() {
    return "relight-sequence '" + path("scene.relume") +
           "' --light-orbit 30 --frames 8 --rotate-step 45 --exposure auto ";
  }
  // The lowest PSNR (dB, peak 255) of the video's frames against the PNG frames, frame k
  // against PNG k + shift.
  static double lowest_psnr(const DecodedVideo& video, std::size_t shift = 0) {
    double lowest = 1e9;
    for (std::size_t k = 0; k + shift < video.frames.size(); ++k) {
      const Image png = read_image(path("png/" + std::to_string(k + shift) + ".png"));
      double squared = 0;
      for (std::size_t i = 0; i < video.frames[k].size(); ++i)
        squared += std::pow(video.frames[k][i] - 255.0 * png.pixels[i], 2);
      lowest = std::min(lowest, 10 * std::log10(255.0 * 255.0 * video.frames[k].size() / squared));
    }
    return lowest;
  }
};

TEST_F(VideoOutput, EveryFrameOfTheDefaultVideoIsThePngFrame) {
  const auto result = run_or_fail(sequence() + "--video '" + path("orbit.mp4") + "' --report '" +
                                  path("report.json") + "'");
  EXPECT_NE(result.output.find("wrote " + path("orbit.mp4") + ": 8 frames"), std::string::npos)
      << result.output;
  std::ifstream in(path("report.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  const DecodedVideo video = decode(path("orbit.mp4"));
  EXPECT_EQ(video.codec, report["video"]["codec"] == "libx264" ? "h264" : "mpeg4");
  ASSERT_EQ(video.frames.size(), 8u);
  ASSERT_EQ(video.width, 64);
  ASSERT_EQ(video.height, 48);
  // Lossy (4:2:0 chroma on a 64 x 48 frame of sharp spheres), yet the same pictures, in order:
  // against the next frame's PNG it is far lower.
  const double same = lowest_psnr(video);
  EXPECT_GT(same, 28);
  EXPECT_LT(lowest_psnr(video, 1), same - 6);
}

TEST_F(VideoOutput, MpegFourInMatroskaOnRequest) {
  run_or_fail(sequence() + "--video '" + path("orbit.mkv") + "' --codec mpeg4 --fps 12");
  const DecodedVideo video = decode(path("orbit.mkv"));
  EXPECT_EQ(video.codec, "mpeg4");
  ASSERT_EQ(video.frames.size(), 8u);
  EXPECT_GT(lowest_psnr(video), 26);
}

// 4:2:0 chroma needs even sizes: a 64 x 43 field lost its last row without a word.
TEST_F(VideoOutput, AnOddFrameSizeIsEncodedOneRowShorterWithANote) {
  run_or_fail("synth -o '" + path("odd") + "' --size 64x43 --lights 30 --samples 1");
  run_or_fail("compress '" + path("odd") + "' -o '" + path("odd.relume") +
              "' --clusters 3 --terms 2 --residual 3");
  const auto result = run_or_fail("relight-sequence '" + path("odd.relume") +
                                  "' --light-orbit 30 --frames 2 --video '" + path("odd.mp4") +
                                  "'");
  EXPECT_NE(result.output.find("video " + path("odd.mp4") +
                               ": frames of 64x43 are encoded as 64x42 (its chroma needs even "
                               "sizes): the last row is left out; the image frames keep it"),
            std::string::npos)
      << result.output;
  const DecodedVideo video = decode(path("odd.mp4"));
  EXPECT_EQ(video.frames.size(), 2u);
  EXPECT_EQ(video.width, 64);
  EXPECT_EQ(video.height, 42);
  EXPECT_EQ(run_or_fail(sequence() + "--video '" + path("even.mp4") + "'")
                .output.find("encoded as"),
            std::string::npos);
}

TEST_F(VideoOutput, BadTargetsAreRefusedBeforeAnyWork) {
  const auto unknown = testing::run_relume(sequence() + "-o '" + path("none/%d.png") +
                                           "' --video '" + path("orbit.xyz") + "'");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find("no video container"), std::string::npos) << unknown.output;
  EXPECT_FALSE(fs::exists(path("none")));
  const auto codec =
      testing::run_relume(sequence() + "--video '" + path("x.mp4") + "' --codec no-such-codec");
  EXPECT_EQ(codec.exit_code, 1);
  EXPECT_NE(codec.output.find("no-such-codec"), std::string::npos) << codec.output;
  EXPECT_FALSE(fs::exists(path("x.mp4")));
  run_or_fail(sequence() + "--video '" + path("taken.mp4") + "'");
  const auto again = testing::run_relume(sequence() + "--video '" + path("taken.mp4") + "'");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.output.find("exists"), std::string::npos) << again.output;
  EXPECT_EQ(testing::run_relume(sequence()).exit_code, 1) << "neither -o nor --video";
  for (const auto& entry : fs::directory_iterator(path("")))
    EXPECT_EQ(entry.path().string().find("relume-partial"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace relume
