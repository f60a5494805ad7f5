// Small helpers shared by the figure sources (figures*.cpp): numbers and names in alt text,
// iteration ticks, the metric's range on an axis. Internal to the plot module.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "feint/plot/figures.hpp"

namespace feint::plot::figure_detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline double value(const std::optional<double>& v) { return v ? *v : kNaN; }

// A label says the test found a difference: M>R, M<R, A>B, A<B.
inline bool differs(const tables::TidyRow& row) {
  return row.label.find('>') != std::string::npos || row.label.find('<') != std::string::npos;
}

inline std::string p_threshold(double alpha) {
  std::string s = fmt::format("{:g}", alpha);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);  // APA: no leading zero
  return s;
}

inline std::string adjust_words(const std::string& p_adjust) {
  // Marks from unadjusted p say so: the report's claims may rest on adjusted ones.
  return p_adjust.empty() || p_adjust == "none" ? ", unadjusted" : fmt::format(", {}", p_adjust);
}

// Iteration ticks: 1 and round numbers up to the last iteration.
inline std::vector<double> iteration_ticks(long long first, long long last) {
  std::vector<double> t = detail::nice_ticks(static_cast<double>(first), static_cast<double>(last));
  if (t.size() >= 2 && first >= 0 && t.front() - static_cast<double>(first) >= (t[1] - t[0]) / 2) {
    t.insert(t.begin(), static_cast<double>(first));
  }
  return t;
}

inline std::string condition_name(const std::string& c) {
  return c.empty() ? "all participants" : c;
}

// The metric's range as axis bounds (only the finite ends).
inline void bound(Axis& a, const MetricRange& r) {
  if (std::isfinite(r.lo)) a.bound_min = r.lo;
  if (std::isfinite(r.hi)) a.bound_max = r.hi;
}

inline double clip(double v, const MetricRange& r) {
  return std::isnan(v) ? v : std::clamp(v, r.lo, r.hi);
}

inline std::string number(double v) {
  if (!std::isfinite(v)) return "NA";
  if (std::fabs(v) < 0.005) v = 0;  // no "-0.00"
  return fmt::format("{:.2f}", v);
}

// "A and B", "A, B and C".
inline std::string and_list(const std::vector<std::string>& names) {
  if (names.empty()) return "";
  if (names.size() == 1) return names[0];
  std::string s;
  for (std::size_t i = 0; i + 1 < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + " and " + names.back();
}

inline std::vector<std::string> condition_names(const std::vector<std::string>& cs) {
  std::vector<std::string> out;
  for (const auto& c : cs) out.push_back(condition_name(c));
  return out;
}

inline std::string capitalise(std::string s) {
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

}  // namespace feint::plot::figure_detail
