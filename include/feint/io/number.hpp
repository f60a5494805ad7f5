// feint/io/number.hpp - strict number parsing, round-trip number formatting, JSON/text helpers.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace feint::io {

/// Parses a number exactly as strtod reads its decimal form in the C locale: optional sign (one),
/// digits with an optional decimal point, optional exponent (`e`/`E`, optional sign, digits); the
/// correctly rounded double, an underflow read as strtod reads it (0 or a subnormal). Spaces and
/// tabs around the number are ignored (CSV cells are often padded). Rejects (nullopt) what formats.md
/// declares invalid although strtod accepts it: `inf`, `nan`, hexadecimal (`0x1p3`), an overflow
/// (`1e999`); and what strtod does not accept whole: empty text, `+-2`, `1,5`, `1e`, trailing
/// text. See docs/scoring.md "How numbers are read".
std::optional<double> parse_double(std::string_view text) noexcept;

/// Parses a whole number (optional single sign, decimal digits, surrounding spaces and tabs
/// ignored) that fits in a long long; nullopt otherwise.
std::optional<long long> parse_integer(std::string_view text) noexcept;

namespace detail {
/// Length of the longest prefix of `s` that is a decimal number in strtod's grammar (sign,
/// digits, point, exponent with digits); 0 when there is none.
std::size_t decimal_prefix(std::string_view s) noexcept;
/// The loaders' fast path for plain decimals such as `0.527` or `-12.25` (at most 15 digits, no
/// exponent, no blanks): the digits form an exact integer m < 2^53 and 10^k is exact, so m / 10^k is
/// the correctly rounded value (Clinger 1990, "How to read floating point numbers accurately"),
/// identical to parse_double's. Anything else goes to parse_double.
[[gnu::always_inline]] inline std::optional<double> parse_decimal_fast(std::string_view s) noexcept {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const char* p = s.data();
  const char* const e = p + s.size();
  const bool negative = p < e && *p == '-';
  if (negative) ++p;
  unsigned long long mantissa = 0;
  int digits = 0, fraction = 0;
  while (p < e && static_cast<unsigned>(*p - '0') < 10U) {
    mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
    ++digits;
    ++p;
  }
  if (p < e && *p == '.') {
    ++p;
    while (p < e && static_cast<unsigned>(*p - '0') < 10U) {
      mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
      ++digits;
      ++fraction;
      ++p;
    }
  }
  if (p != e || digits == 0 || digits > 15) return parse_double(s);
  const double v = static_cast<double>(mantissa) / kPow10[fraction];
  return negative ? -v : v;
}

}  // namespace detail

/// Shortest text that reads back as exactly the same double (e.g. `0.1`, `1e-300`).
/// NaN (feint's "no value") is written as the empty string, so CSV cells stay empty, never `nan`.
std::string format_double(double value);

/// A JSON string literal: quotes, backslash and control characters escaped (RFC 8259).
std::string json_quote(std::string_view text);

/// A JSON number (shortest round-trip text); `null` for NaN and infinities, which JSON lacks.
std::string json_number(double value);

/// Removes leading and trailing ASCII blanks (space, tab).
std::string_view trim(std::string_view text) noexcept;

/// ASCII lower-case copy (column names and labels are matched case-insensitively).
std::string to_lower(std::string_view text);

}  // namespace feint::io
