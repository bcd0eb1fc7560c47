// Parsing frame patterns.
#include "options/frame_pattern.hpp"

#include <cctype>
#include <cstdint>
#include <relume/error.hpp>

namespace relume {

FramePattern::FramePattern(const std::string& pattern, int start_number)
    : start_number_(start_number) {
  const auto fail = [&](const std::string& why) {
    throw Error("output pattern '" + pattern + "' " + why +
                " (frames/%04d.png or frames/####.png)");
  };
  const std::size_t percent = pattern.find('%');
  const std::size_t hash = pattern.find('#');
  if ((percent == std::string::npos) == (hash == std::string::npos))
    fail("needs exactly one frame-number conversion, %d or a run of #");
  std::size_t end = 0;
  if (percent != std::string::npos) {
    end = percent + 1;
    while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) ++end;
    if (end == pattern.size() || pattern[end] != 'd')
      fail("may hold only %d with a width such as %04d");
    const std::string width = pattern.substr(percent + 1, end - percent - 1);
    width_ = width.empty() ? 0 : std::stoi(width);
    if (width_ > 16) fail("asks for more than 16 digits");
    before_ = pattern.substr(0, percent);
    after_ = pattern.substr(end + 1);
  } else {
    end = hash;
    while (end < pattern.size() && pattern[end] == '#') ++end;
    width_ = static_cast<int>(end - hash);
    before_ = pattern.substr(0, hash);
    after_ = pattern.substr(end);
  }
  if (after_.find_first_of("%#") != std::string::npos)
    fail("needs exactly one frame-number conversion");
  if (start_number < 0)
    throw Error("--start-number must be >= 0, got " + std::to_string(start_number));
}

std::string FramePattern::path(int index) const {
  // In 64 bits: --start-number 2147483647 and a second frame overflowed an int.
  std::string number = std::to_string(std::int64_t(start_number_) + index);
  if (static_cast<int>(number.size()) < width_)
    number.insert(0, std::size_t(width_) - number.size(), '0');
  return before_ + number + after_;
}

}  // namespace relume
