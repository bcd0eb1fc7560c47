// Implementation of the tokenizer and the locale-independent number parsers.
#include "core/text_numbers.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

namespace relume {

std::vector<std::string_view> split_blank_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = line.find_first_not_of(blank_characters);
  while (start != std::string_view::npos) {
    const std::size_t end = line.find_first_of(blank_characters, start);
    fields.push_back(line.substr(start, end == std::string_view::npos ? end : end - start));
    start = end == std::string_view::npos ? end : line.find_first_not_of(blank_characters, end);
  }
  return fields;
}

std::string_view trim_blanks(std::string_view line) {
  const std::size_t first = line.find_first_not_of(blank_characters);
  if (first == std::string_view::npos) return {};
  return line.substr(first, line.find_last_not_of(blank_characters) - first + 1);
}

bool is_blank_or_comment(std::string_view line) {
  const std::string_view trimmed = trim_blanks(line);
  return trimmed.empty() || trimmed.front() == '#';
}

ParsedNumber parse_number_token(std::string_view token, bool decimal_comma) {
  std::string text(token);
  if (decimal_comma)
    for (char& c : text)
      if (c == ',') c = '.';
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+' && last - first > 1 && first[1] != '-') ++first;
  double value = 0;
  const auto [end, error] = std::from_chars(first, last, value);
  if (end != last || first == last) return {};
  if (error == std::errc::result_out_of_range) {
    // Underflow (1e-400) rounds to zero; overflow (1e400) is not a finite number.
    const std::string_view digits(first, std::size_t(last - first));
    const auto e = digits.find_first_of("eE");
    const bool negative_exponent =
        e != std::string_view::npos && e + 1 < digits.size() && digits[e + 1] == '-';
    if (negative_exponent) return {ParsedNumber::Status::number, 0.0};
    return {ParsedNumber::Status::not_finite, 0.0};
  }
  if (error != std::errc()) return {};
  if (!std::isfinite(value)) return {ParsedNumber::Status::not_finite, value};
  return {ParsedNumber::Status::number, value};
}

std::optional<double> parse_finite_double(std::string_view token) {
  const ParsedNumber parsed = parse_number_token(token);
  if (parsed.status != ParsedNumber::Status::number) return std::nullopt;
  return parsed.value;
}

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::optional<std::uint64_t> parse_unsigned(std::string_view token) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size())
    return std::nullopt;
  return value;
}

}  // namespace relume
