// feint/io/number.hpp - strict number parsing, round-trip number formatting, JSON/text helpers.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace feint::io {

/// Parses a decimal number the way formats.md requires: a decimal point, optional exponent, optional
/// sign, surrounding blanks ignored. Rejects (returns nullopt) empty text, `nan`, `inf`, thousands
/// separators, decimal commas, hex and trailing garbage.
std::optional<double> parse_double(std::string_view text) noexcept;

/// Parses a whole number (optional sign, surrounding blanks ignored); nullopt otherwise.
std::optional<long long> parse_integer(std::string_view text) noexcept;

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
