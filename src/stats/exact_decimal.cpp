#include "feint/stats/exact_decimal.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "shifted.hpp"

namespace feint::stats {

namespace {

__extension__ using i128 = __int128;

/// value = mantissa * 10^-scale (scale may be negative for "12e3").
struct Decimal {
  i128 mantissa = 0;
  int scale = 0;
};

constexpr int kMaxDigits = 36;  // |mantissa| < 10^36 < 2^127 / 100: room for the rescaling below

[[noreturn]] void bad(std::string_view text, std::string_view why) {
  throw InvalidData(fmt::format("'{}' is not a decimal number ({})", text, why));
}

Decimal parse_decimal(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  std::size_t end = text.size();
  while (end > i && (text[end - 1] == ' ' || text[end - 1] == '\t' || text[end - 1] == '\r')) --end;
  bool negative = false;
  if (i < end && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  Decimal d;
  int digits = 0, after_point = 0;
  bool any = false, point = false;
  for (; i < end; ++i) {
    const char c = text[i];
    if (c >= '0' && c <= '9') {
      any = true;
      if (d.mantissa != 0 || c != '0') ++digits;
      if (digits > kMaxDigits) {
        // Digits beyond the 36th change the value by less than 1e-35 relative, far below what
        // a double holds: dropped (the number stays in range, only its tail is cut).
        if (!point) --after_point;  // an integer digit dropped: one power of ten fewer
        continue;
      }
      d.mantissa = d.mantissa * 10 + (c - '0');
      if (point) ++after_point;
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!any) bad(text, "no digits");
  int exponent = 0;
  if (i < end && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < end && (text[i] == '+' || text[i] == '-')) eneg = text[i++] == '-';
    if (i == end) bad(text, "empty exponent");
    for (; i < end && text[i] >= '0' && text[i] <= '9'; ++i) {
      exponent = exponent * 10 + (text[i] - '0');
      if (exponent > 400) bad(text, "exponent out of range");
    }
    if (eneg) exponent = -exponent;
  }
  if (i != end) bad(text, "unexpected character");
  d.scale = after_point - exponent;
  if (negative) d.mantissa = -d.mantissa;
  return d;
}

// The correctly rounded double of a decimal text that parse_decimal accepted.
double read_double(std::string_view text) {
  std::size_t i = 0, end = text.size();
  while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
  while (end > i && (text[end - 1] == ' ' || text[end - 1] == '\t' || text[end - 1] == '\r')) --end;
  if (i < end && text[i] == '+') ++i;
  double v = 0;
  const auto [p, ec] = std::from_chars(text.data() + i, text.data() + end, v);
  if (ec == std::errc::result_out_of_range) {
    // Only an underflow can get here (parse_decimal bounds the exponent): strtod's value.
    v = std::strtod(std::string(text.substr(i, end - i)).c_str(), nullptr);
  } else if (ec != std::errc() || p != text.data() + end) {
    bad(text, "unexpected character");
  }
  return v;
}

i128 pow10(int k, std::string_view context) {
  if (k < 0 || k > 38) throw InvalidData(fmt::format("{}: decimal scales too far apart", context));
  i128 p = 1;
  for (int j = 0; j < k; ++j) p *= 10;
  return p;
}

long double pow10l(int k) {
  long double p = 1;
  for (int j = 0; j < (k < 0 ? -k : k); ++j) p *= 10;  // exact up to 10^27
  return k < 0 ? 1 / p : p;
}

/// All values of all groups on a common scale, the first value subtracted exactly.
struct ExactGroups {
  std::vector<std::vector<long double>> a;
  long double shift = 0;
  long double scale = 1;
  std::optional<long double> total;  // exact sum of every value * scale, when it fits
};

ExactGroups read_exact(std::span<const std::vector<std::string>> groups) {
  std::vector<std::vector<Decimal>> dec(groups.size());
  int scale = std::numeric_limits<int>::min();
  bool any = false;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (const auto& t : groups[g]) {
      dec[g].push_back(parse_decimal(t));
      scale = std::max(scale, dec[g].back().scale);
      any = true;
    }
  }
  ExactGroups out;
  out.a.resize(groups.size());
  if (!any) return out;
  // A common scale no coarser than the finest value; ints = mantissa * 10^(scale - own scale).
  auto to_int = [&](const Decimal& d, std::string_view what) -> i128 {
    const i128 f = pow10(scale - d.scale, what);
    const i128 limit = std::numeric_limits<i128>::max() / 4;
    if (d.mantissa != 0 && (f > limit / (d.mantissa < 0 ? -d.mantissa : d.mantissa)))
      throw InvalidData(fmt::format("{}: too many digits to read exactly", what));
    return d.mantissa * f;
  };
  i128 shift = 0, total = 0;
  bool first = true, total_ok = true;
  for (std::size_t g = 0; g < dec.size(); ++g) {
    for (std::size_t i = 0; i < dec[g].size(); ++i) {
      const i128 v = to_int(dec[g][i], groups[g][i]);
      if (first) {
        shift = v;
        first = false;
      }
      // |v|, |shift| < max / 4: the difference cannot overflow; beyond 2^64 long double rounds it.
      out.a[g].push_back(static_cast<long double>(v - shift));
      if (total_ok) total_ok = !__builtin_add_overflow(total, v, &total);
    }
  }
  // The final results need shift / 10^scale; with scale < 0 the shift is an integer times 10^-scale.
  out.scale = pow10l(scale);
  out.shift = static_cast<long double>(shift) / out.scale;
  if (total_ok) out.total = static_cast<long double>(total);
  return out;
}

detail::Shifted single(std::span<const std::string> text) {
  std::vector<std::vector<std::string>> one(1, std::vector<std::string>(text.begin(), text.end()));
  ExactGroups e = read_exact(one);
  detail::Shifted s;
  s.a = std::move(e.a[0]);
  s.shift = e.shift;
  s.scale = e.scale;
  s.total = e.total;
  return s;
}

}  // namespace

Summary summarize_decimal(std::span<const std::string> text) {
  return detail::summary_of(single(text));
}

std::optional<double> autocorr_lag1_decimal(std::span<const std::string> text) {
  return detail::autocorr_of(single(text));
}

Description describe_decimal(std::span<const std::string> text, double conf_level) {
  const detail::Shifted sh = single(text);
  // Order statistics are values of the file: each text read once, correctly rounded (as the
  // loaders read it), never rebuilt from the shifted integers (0.3, not 0.2999999999999998).
  std::vector<double> values;
  values.reserve(text.size());
  for (const auto& t : text) values.push_back(read_double(t));
  return detail::describe_from(std::move(values), detail::summary_of(sh),
                               [&] { return detail::autocorr_of(sh); }, conf_level);
}

AnovaTable one_way_anova_table_decimal(std::span<const std::vector<std::string>> groups) {
  ExactGroups e = read_exact(groups);
  return detail::anova_of(e.a, e.scale);
}

}  // namespace feint::stats
