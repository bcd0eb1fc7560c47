// Implementation of the number-or-auto option values.
#include "options/number_or_auto.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "core/text_numbers.hpp"

namespace relume {

double parse_finite_number(const std::string& text, const std::string& option,
                           const std::string& unit, double limit) {
  std::size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(std::abs(value) <= limit)) {
    const std::string range = std::isfinite(limit) ? " from -" + number_text(limit) + " to " +
                                                         number_text(limit)
                                                   : "";
    throw Error(option + " must be a number of " + unit + range + " or 'auto', got '" + text +
                "'");
  }
  return value;
}

CLI::Validator number_or_auto(const std::string& option, const std::string& unit, double limit) {
  return CLI::Validator(
      [option, unit, limit](const std::string& text) {
        try {
          if (text != "auto") parse_finite_number(text, option, unit, limit);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      },
      "NUMBER|auto");
}

}  // namespace relume
