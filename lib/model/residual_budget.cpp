// Implementation of the residual budget (relume/residual_budget.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <relume/error.hpp>
#include <relume/residual_budget.hpp>

namespace relume {

ResidualBudget ResidualBudget::parse(const std::string& text) {
  const auto bad = [&] {
    return Error("residual budget '" + text +
                 "' is invalid: expected a count of entries per function (for example 10) or a "
                 "percentage of the lights (for example 5%)");
  };
  if (text.empty()) throw bad();
  const bool is_percent = text.back() == '%';
  const std::string number = is_percent ? text.substr(0, text.size() - 1) : text;
  if (number.empty()) throw bad();
  char* end = nullptr;
  ResidualBudget budget;
  if (is_percent) {
    const double value = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size() || !std::isfinite(value) || value < 0 || value > 100)
      throw bad();
    budget.percent = value;
  } else {
    const long value = std::strtol(number.c_str(), &end, 10);
    if (end != number.c_str() + number.size() || value < 0 || value > 1 << 24) throw bad();
    budget.entries = static_cast<int>(value);
  }
  return budget;
}

int ResidualBudget::entries_for(int lights) const {
  if (percent < 0) return std::min(entries, lights);
  return std::min(lights, static_cast<int>(std::lround(percent / 100.0 * lights)));
}

std::string ResidualBudget::describe() const {
  if (percent < 0) return std::to_string(entries);
  char text[32];
  std::snprintf(text, sizeof text, "%g%%", percent);
  return text;
}

}  // namespace relume
