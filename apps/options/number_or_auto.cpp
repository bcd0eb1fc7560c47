// Implementation of the number-or-auto option values.
#include "options/number_or_auto.hpp"

#include <cmath>
#include <relume/error.hpp>

namespace relume {

double parse_finite_number(const std::string& text, const std::string& option,
                           const std::string& unit) {
  std::size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !std::isfinite(value))
    throw Error(option + " must be a number of " + unit + " or 'auto', got '" + text + "'");
  return value;
}

CLI::Validator number_or_auto(const std::string& option, const std::string& unit) {
  return CLI::Validator(
      [option, unit](const std::string& text) {
        try {
          if (text != "auto") parse_finite_number(text, option, unit);
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      },
      "NUMBER|auto");
}

}  // namespace relume
