// Differential target: feint reads a number exactly when strtod (C locale) reads the whole text
// as a finite decimal number, and then to the same bits.
#include <locale.h>
#include <stdlib.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "feint/io/number.hpp"
#include "harness.hpp"

namespace feint::fuzz {

namespace {

std::optional<double> oracle(const std::string& text) {
  static const locale_t c_locale = ::newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  // The documented differences from bare strtod: blanks (space, tab) around the number are
  // trimmed; any other leading white space, hex, inf and nan are not numbers; overflow is invalid.
  const std::string_view t = io::trim(text);
  if (t.empty()) return std::nullopt;
  const std::string s(t);
  const unsigned char c0 = static_cast<unsigned char>(s[0]);
  if (!(c0 == '+' || c0 == '-' || c0 == '.' || (c0 >= '0' && c0 <= '9'))) return std::nullopt;
  if (s.find_first_of("xXiInN") != std::string::npos) return std::nullopt;
  if (s.find('\0') != std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double v = ::strtod_l(s.c_str(), &end, c_locale);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool same(std::optional<double> a, std::optional<double> b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || std::memcmp(&*a, &*b, sizeof(double)) == 0;
}

}  // namespace

int number(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto want = oracle(text);
  detail::check(same(io::parse_double(text), want), "parse_double differs from strtod");
  if (!text.empty() && io::trim(text).size() == text.size()) {
    // The loaders' fast path sees cells without surrounding blanks.
    detail::check(same(io::detail::parse_decimal_fast(text), want),
                  "parse_decimal_fast differs from strtod");
  }
  const auto i = io::parse_integer(text);
  if (i) {
    // A whole number is also a number, of the same value when it is exactly representable.
    const auto d = io::parse_double(text);
    detail::check(d.has_value(), "parse_integer accepts what parse_double rejects");
    if (*i > -(1LL << 53) && *i < (1LL << 53)) {
      detail::check(*d == static_cast<double>(*i), "parse_integer and parse_double disagree");
    }
  }
  return 0;
}

}  // namespace feint::fuzz
