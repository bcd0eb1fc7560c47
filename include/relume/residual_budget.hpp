// relume/residual_budget.hpp: how many residual entries each compressed function keeps (paper
// section 3.4), as `relume compress --residual` and relume.compress(residual=...) say it: a count
// of entries per function, or a percentage of the lights.
#pragma once

#include <string>

namespace relume {

struct ResidualBudget {
  int entries = 0;        // used when percent < 0
  double percent = -1.0;  // >= 0: round(percent / 100 * lights) entries

  // "N" (a count, 0 to 2^24) or "P%" (0 <= P <= 100); throws Error naming the bad text.
  static ResidualBudget parse(const std::string& text);

  // Entries per function for a field of `lights` lights (never more than `lights`).
  int entries_for(int lights) const;
  std::string describe() const;  // "10" or "5%", what parse reads back
  bool operator==(const ResidualBudget&) const = default;
};

}  // namespace relume
