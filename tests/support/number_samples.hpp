// Number texts for property tests of numeric inputs: a fixed list of edges (0 and -0, the range
// limits the commands use, the largest and smallest doubles and ints, values that overflow a
// double, inf and nan in their spellings, hexadecimal floats) mixed with random magnitudes of
// either sign, drawn from a seeded generator so that a failure repeats.
#pragma once

#include <random>
#include <string>

namespace relume::testing {

class NumberSamples {
 public:
  explicit NumberSamples(std::uint64_t seed) : random_(seed) {}

  // One number as text: an edge about half of the time, else sign x 10^U(-12, 12).
  std::string next();
  // Three of them joined by commas, as x,y,z and r,g,b options take them.
  std::string next_triple();

 private:
  std::mt19937_64 random_;
};

}  // namespace relume::testing
