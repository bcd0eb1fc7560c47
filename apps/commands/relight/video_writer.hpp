// `relight-sequence --video OUT`: frames encoded straight into a video file with FFmpeg's
// libraries (libavformat, libavcodec, libswscale), no image files in between. The container
// comes from the extension (.mp4, .mkv, .mov, .webm, ...); the codec is the first of a
// preference list that this FFmpeg build has: H.264 through libx264 (CRF 18, near transparent)
// for MP4/MKV/MOV, then MPEG-4 part 2; VP9 then VP8 (libvpx) for WebM; or one named with --codec.
//
// Frames are display-referred like PNG outputs (exposed, clamped, sRGB-encoded, 8 bits), then
// converted to YUV 4:2:0 with the BT.601 matrix in limited range and tagged as such (sRGB
// transfer, BT.709 primaries), so that players and decoders that read the tags show the same
// colours as the PNGs. 4:2:0 needs even sizes: an odd last column or row is left out.
// The file is written beside the target under a temporary name and renamed when finished, so an
// interrupted or failed run leaves no half-written video.
#pragma once

#include <filesystem>
#include <memory>
#include <relume/image.hpp>
#include <string>

namespace relume {

class VideoWriter {
 public:
  // Throws Error naming the file when FFmpeg knows no container for its extension, has none of
  // the preferred encoders (or not `codec`), or cannot open the file; or for a frame size under
  // 2 x 2 or a frame rate outside [1, 240].
  VideoWriter(const std::filesystem::path& path, int width, int height, int frames_per_second,
              const std::string& codec = "");
  ~VideoWriter();  // removes the temporary file unless finish() succeeded

  // The container and encoder checks of the constructor alone, before any work is done.
  static void check_target(const std::filesystem::path& path, const std::string& codec = "");
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Encodes one frame (width x height, 1 or 3+ channels, linear) exposed by 2^exposure stops.
  void add_frame(const Image& image, double exposure);
  // Flushes the encoder, writes the trailer and renames the file into place.
  void finish();

  std::string codec_name() const;  // the encoder used, e.g. "libx264"
  int frames() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace relume
