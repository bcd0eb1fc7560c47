// Option values that are a number or the word auto (--rotate DEG|auto, --exposure STOPS|auto):
// the parse and the CLI11 check that makes a malformed value a usage error.
#pragma once

#include <CLI/CLI.hpp>
#include <limits>
#include <string>

namespace relume {

// `text` as a finite number of magnitude at most `limit`. Throws Error "OPTION must be a number
// of UNIT [from -LIMIT to LIMIT] or 'auto', got ..." otherwise.
double parse_finite_number(const std::string& text, const std::string& option,
                           const std::string& unit,
                           double limit = std::numeric_limits<double>::infinity());

// Accepts "auto" and what parse_finite_number accepts.
CLI::Validator number_or_auto(const std::string& option, const std::string& unit,
                              double limit = std::numeric_limits<double>::infinity());

}  // namespace relume
