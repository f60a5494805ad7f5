#include "feint/io/number.hpp"

#include <locale.h>
#include <stdlib.h>

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace feint::io {

std::string_view trim(std::string_view text) noexcept {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

std::string to_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

namespace detail {

std::size_t decimal_prefix(std::string_view s) noexcept {
  std::size_t i = 0;
  const std::size_t n = s.size();
  if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < n && static_cast<unsigned>(s[i] - '0') < 10U) ++i, ++digits;
  if (i < n && s[i] == '.') {
    ++i;
    while (i < n && static_cast<unsigned>(s[i] - '0') < 10U) ++i, ++digits;
  }
  if (digits == 0) return 0;
  // An exponent counts only with at least one digit ("1e" is the number 1 followed by "e").
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < n && (s[j] == '+' || s[j] == '-')) ++j;
    if (j < n && static_cast<unsigned>(s[j] - '0') < 10U) {
      while (j < n && static_cast<unsigned>(s[j] - '0') < 10U) ++j;
      i = j;
    }
  }
  return i;
}

}  // namespace detail

namespace {

// strtod in the C locale whatever the process locale is (a decimal comma locale must not change
// what a file means).
double strtod_c(const std::string& text) noexcept {
  static const locale_t c_locale = ::newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  return ::strtod_l(text.c_str(), nullptr, c_locale);
}

}  // namespace

std::optional<double> parse_double(std::string_view text) noexcept {
  text = trim(text);
  // The decimal subject sequence of strtod (C17 7.22.1.3), and nothing after it. strtod's other
  // forms (hexadecimal, inf, nan) are not decimal numbers (formats.md) and fail this test.
  if (text.empty() || detail::decimal_prefix(text) != text.size()) return std::nullopt;
  std::string_view body = text;
  if (body.front() == '+') body.remove_prefix(1);  // from_chars takes '-' only
  double value = 0;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value,
                                         std::chars_format::general);
  if (ec == std::errc() && end == body.data() + body.size()) return value;
  if (ec != std::errc::result_out_of_range) return std::nullopt;
  // Out of range: an underflow reads as strtod reads it (0 or a subnormal, correctly rounded, sign
  // kept); an overflow is infinite and invalid.
  try {
    value = strtod_c(std::string(text));
  } catch (...) {
    return std::nullopt;
  }
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view text) noexcept {
  text = trim(text);
  // One optional sign, then decimal digits only (strtoll's decimal form, read whole).
  std::string_view digits = text;
  if (!digits.empty() && (digits.front() == '+' || digits.front() == '-')) digits.remove_prefix(1);
  if (digits.empty() || !(digits.front() >= '0' && digits.front() <= '9')) return std::nullopt;
  std::string_view body = text.front() == '+' ? digits : text;  // from_chars takes '-' only
  long long value = 0;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (ec != std::errc() || end != body.data() + body.size()) return std::nullopt;
  return value;
}

std::string json_quote(std::string_view text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto u = static_cast<unsigned char>(ch);
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (u < 0x20) {
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(u));
        } else {
          out += ch;
        }
    }
  }
  out += '"';
  return out;
}

std::string json_number(double value) {
  return std::isfinite(value) ? format_double(value) : std::string("null");
}

std::string format_double(double value) {
  if (std::isnan(value)) return {};
  return fmt::format("{}", value);  // fmt's default is the shortest round-trip representation
}

}  // namespace feint::io
