// Implementation of the number texts of property tests (number_samples.hpp).
#include "support/number_samples.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>

namespace relume::testing {
namespace {

const char* const edges[] = {
    "0",    "-0",   "1",    "-1",   "0.5",  "2",       "40",       "40.5",        "-41",
    "90",   "91",   "128",  "200",  "360",  "1e-30",   "1e-320",   "1e6",         "1e7",
    "1e30", "1e38", "1e39", "1e308", "-1e308", "1e400", "-1e400",  "inf",         "-inf",
    "nan",  "-nan", "NaN",  "Infinity", "0x1p9999", "2147483647", "2147483648", "-2147483649",
    "1e9",  "1.5",  "-0.0001"};

}  // namespace

std::string NumberSamples::next() {
  if (random_() % 2 == 0) return edges[random_() % std::size(edges)];
  const double magnitude = std::pow(10.0, std::uniform_real_distribution<double>(-12, 12)(random_));
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", random_() % 2 ? magnitude : -magnitude);
  return text;
}

std::string NumberSamples::next_triple() { return next() + "," + next() + "," + next(); }

}  // namespace relume::testing
