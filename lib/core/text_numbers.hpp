// Numbers and fields in text files and option values, read the same way everywhere and
// independently of the C locale (std::from_chars): one blank-separated tokenizer (space, tab,
// \v, \f, \r are all blanks) and whole-token number parsers that say why a token is not a number.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace relume {

// The characters that separate fields: " \t\v\f\r".
inline constexpr std::string_view blank_characters = " \t\v\f\r";

// The blank-separated fields of `line`, in order (views into it).
std::vector<std::string_view> split_blank_fields(std::string_view line);

// `line` without leading and trailing blanks.
std::string_view trim_blanks(std::string_view line);

// True when the line has only blanks, or its first non-blank character is '#'.
bool is_blank_or_comment(std::string_view line);

struct ParsedNumber {
  enum class Status { number, not_a_number, not_finite };
  Status status = Status::not_a_number;
  double value = 0;
};

// The whole token as a decimal or scientific number ("1", "-2.5e-3", "+4"; with
// decimal_comma also "0,25"). A token that overflows double, or spells inf or nan, is not_finite.
ParsedNumber parse_number_token(std::string_view token, bool decimal_comma = false);

// A finite number, or nullopt.
std::optional<double> parse_finite_double(std::string_view token);

// `value` as messages show it: the shortest of fixed and scientific, 6 significant digits ("128",
// "0.5", "1e+300", "inf", "nan").
std::string number_text(double value);

// A whole token of decimal digits that fits 64 bits, or nullopt.
std::optional<std::uint64_t> parse_unsigned(std::string_view token);

}  // namespace relume
