// Checks of numeric option values while the command line is parsed. Every floating-point option
// of every command refuses inf, nan and values that overflow a double: CLI11 converts them like
// any number, and a command then ran with them (`relume sky --sun-elevation inf` wrote a map
// without a sun). Options whose 0 means "not given" refuse 0 and negative values when given.
#pragma once

#include <CLI/CLI.hpp>

namespace relume {

// Adds the check to each option of `app` and of its commands (at any depth) whose values are
// floating-point numbers (CLI11's type name FLOAT, also in lists and x,y,z triples). A value
// that is not finite is a usage error "OPTION: must be a finite number, got 'VALUE'".
void refuse_non_finite_numbers(CLI::App& app);

// A check for an option whose default 0 means "none" (--target-bytes-per-pixel 0 was silently no
// target): a given value <= 0 is a usage error "OPTION: must be > 0, got 'VALUE'".
CLI::Validator positive_number();

}  // namespace relume
