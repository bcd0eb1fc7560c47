// Frame file names of an image sequence, as ffmpeg and Nuke write them: a printf conversion
// (frames/%04d.png, %d) or a run of hashes (frames/####.png: four digits, zero-padded), exactly
// one per pattern, numbered from --start-number.
#pragma once

#include <string>

namespace relume {

class FramePattern {
 public:
  // Throws Error naming the pattern when it has no frame number, more than one, or a printf
  // conversion other than %d / %0Nd.
  FramePattern(const std::string& pattern, int start_number);

  // The file of frame `index` (0 = the first frame, numbered start_number).
  std::string path(int index) const;

 private:
  std::string before_, after_;
  int width_ = 0;  // zero-padded to this many digits (0: as many as needed)
  int start_number_ = 0;
};

}  // namespace relume
