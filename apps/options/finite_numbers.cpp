// Implementation of the checks of numeric option values.
#include "options/finite_numbers.hpp"

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "core/text_numbers.hpp"

namespace relume {

namespace {

// Whether `text` reads as a number that is not finite: inf, nan, 1e999, or what strtod (CLI11's
// reader of floats) takes beyond the plain decimal forms, such as 0x1p9999.
bool non_finite_number(const std::string& text) {
  if (parse_number_token(text).status == ParsedNumber::Status::not_finite) return true;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && !std::isfinite(value);
}

}  // namespace

void refuse_non_finite_numbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name().find("FLOAT") == std::string::npos) continue;
    // CLI11 puts the option's name before the message; malformed values are left to its own
    // conversion error.
    option->check(CLI::Validator(
        [](const std::string& text) {
          if (!non_finite_number(text)) return std::string();
          return "must be a finite number, got '" + text + "'";
        },
        "", "finite"));
  }
  for (CLI::App* command : app.get_subcommands({})) refuse_non_finite_numbers(*command);
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](const std::string& text) {
        const std::optional<double> value = parse_finite_double(text);
        if (!value || *value > 0) return std::string();
        return "must be > 0, got '" + text + "'";
      },
      "> 0", "positive");
}

}  // namespace relume
