// Numbers, p-values, APA strings and the labels of a test's conclusion as every table writes
// them (see feint/tables/writers.hpp); the records, CSV, JSON, LaTeX and aligned text tables that
// carry them are in writers.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

// ---------------------------------------------------------------------------------------------
// Output formats

OutputFormat parse_output_format(std::string_view name) {
  const std::string n = io::to_lower(io::trim(name));
  if (n == "text" || n == "txt") return OutputFormat::text;
  if (n == "markdown" || n == "md") return OutputFormat::markdown;
  if (n == "latex" || n == "tex") return OutputFormat::latex;
  if (n == "csv") return OutputFormat::csv;
  if (n == "json") return OutputFormat::json;
  throw UsageError(
      fmt::format("--format '{}': expected text, markdown, latex, csv or json", name));
}

std::string_view to_string(OutputFormat format) noexcept {
  switch (format) {
    case OutputFormat::markdown: return "markdown";
    case OutputFormat::latex: return "latex";
    case OutputFormat::csv: return "csv";
    case OutputFormat::json: return "json";
    case OutputFormat::text: break;
  }
  return "text";
}

// ---------------------------------------------------------------------------------------------
// Number formatting

namespace {

// "-0.0000" reads as a sign where there is none: drop the minus when every digit is zero.
std::string drop_negative_zero(std::string s) {
  if (!s.empty() && s.front() == '-' &&
      s.find_first_not_of("0.", 1) == std::string::npos) {
    s.erase(0, 1);
  }
  return s;
}

bool is_whole(double x) { return std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 1e15; }

}  // namespace

std::string format_mean(std::optional<double> value, int decimals) {
  if (!value || std::isnan(*value)) return {};
  if (std::isinf(*value)) return *value > 0 ? "Inf" : "-Inf";
  return drop_negative_zero(fmt::format("{:.{}f}", *value, decimals));
}

std::string format_p(std::optional<double> p, PStyle style) {
  if (!p || std::isnan(*p)) return {};
  if (*p < DBL_MIN) {
    return style == PStyle::latex ? "$< 2.2 \\times 10^{-308}$" : "< 2.2e-308";
  }
  if (*p < 1e-3) {
    const std::string s = fmt::format("{:.1e}", *p);  // "1.5e-04"
    if (style == PStyle::plain) return s;
    const auto e = s.find('e');
    const int exponent = std::stoi(s.substr(e + 1));
    return fmt::format("${} \\times 10^{{{}}}$", s.substr(0, e), exponent);
  }
  return fmt::format("{:.4f}", *p);
}

std::string format_full(std::optional<double> value) {
  if (!value) return {};
  if (std::isinf(*value)) return *value > 0 ? "Inf" : "-Inf";
  return io::format_double(*value);
}

// ---------------------------------------------------------------------------------------------
// APA strings

std::string apa_p(double p) {
  if (std::isnan(p)) return "p = NA";
  if (p < 0.001) return "p < .001";
  std::string s = fmt::format("{:.3f}", p);
  if (s == "1.000") return "p > .999";
  if (s.front() == '0') s.erase(0, 1);
  return "p = " + s;
}

namespace {

std::string apa_df(double df) {
  if (is_whole(df)) return fmt::format("{}", static_cast<long long>(df));
  return fmt::format("{:.2f}", df);
}

// Rank statistics are sums of (mid)ranks: whole or half numbers; others get two decimals.
std::string apa_rank_statistic(double x) {
  if (is_whole(x)) return fmt::format("{}", static_cast<long long>(x));
  std::string s = fmt::format("{:.2f}", x);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// Correlation-like effect sizes (|r| <= 1): no leading zero, as p.
std::string apa_r(double r) {
  std::string s = drop_negative_zero(fmt::format("{:.2f}", r));
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  if (s.rfind("-0.", 0) == 0) s.erase(1, 1);
  return s;
}

std::string apa_two_dec(double x) { return drop_negative_zero(fmt::format("{:.2f}", x)); }

std::string bayes_factor_text(double log_bf10) {
  // The direction with BF >= 1 is printed (BF01 = 4.2 reads better than BF10 = 0.24).
  const bool for_h1 = log_bf10 >= 0;
  const double l = std::fabs(log_bf10);
  const char* name = for_h1 ? "BF\u2081\u2080" : "BF\u2080\u2081";
  if (l < std::log(1000.0)) return fmt::format("{} = {:.2f}", name, std::exp(l));
  const double log10v = l / std::log(10.0);
  if (log10v > 300) return fmt::format("{} > 1e300", name);
  return fmt::format("{} = {:.1e}", name, std::exp(l));
}

}  // namespace

std::string apa_string(const stats::TestResult& r) {
  if (!r.computed) {
    return r.note.empty() ? std::string(kNotComputable)
                          : fmt::format("{}: {}", kNotComputable, r.note);
  }
  const std::string& t = r.test;
  const bool rank = t == "wilcoxon_signed_rank" || t == "mann_whitney";
  const bool f_test = t == "anova" || t == "welch_anova" ||
                      (t.empty() && r.statistic_name == "F");
  const bool chi2 = t == "kruskal_wallis" || r.statistic_name == "chi-squared" ||
                    r.statistic_name == "Kruskal-Wallis chi-squared";
  std::string out;
  if (t == "tost") out = "TOST: ";
  const double stat = r.statistic.value_or(std::nan(""));
  if (rank) {
    const std::string name = r.statistic_name.empty()
                                 ? (t == "mann_whitney" ? std::string("W") : std::string("V"))
                                 : r.statistic_name;
    out += fmt::format("{} = {}", name, apa_rank_statistic(stat));
  } else if (f_test) {
    out += fmt::format("F({}, {}) = {}", r.df ? apa_df(*r.df) : "NA",
                       r.df2 ? apa_df(*r.df2) : "NA", apa_two_dec(stat));
  } else if (chi2) {
    out += fmt::format("\u03c7\u00b2({}) = {}", r.df ? apa_df(*r.df) : "NA", apa_two_dec(stat));
  } else {
    const std::string name = r.statistic_name.empty() ? std::string("t") : r.statistic_name;
    if (r.df) {
      out += fmt::format("{}({}) = {}", name, apa_df(*r.df), apa_two_dec(stat));
    } else {
      out += fmt::format("{} = {}", name, apa_two_dec(stat));
    }
  }
  if (!r.statistic) out = out.substr(0, out.rfind('=')) + "= NA";
  out += ", ";
  out += r.p_value ? apa_p(*r.p_value) : std::string("p = NA");
  if (r.p_adjusted) {
    std::string adj = apa_p(*r.p_adjusted);  // "p = .021" -> "adjusted p = .021"
    out += ", adjusted " + adj;
  }
  // An interval is printed only when both bounds are finite (a one-sided interval has one
  // infinite bound: "[0.12, Inf]" would read as a typo in a paper).
  auto ci = [&](std::optional<double> lo, std::optional<double> hi, auto fmt_one) {
    if (!lo || !hi || !std::isfinite(*lo) || !std::isfinite(*hi)) return std::string();
    return " [" + fmt_one(*lo) + ", " + fmt_one(*hi) + "]";
  };
  if (rank) {
    if (r.rank_biserial) {
      out += ", r = " + apa_r(*r.rank_biserial) +
             ci(r.rank_biserial_low, r.rank_biserial_high, [](double v) { return apa_r(v); });
    }
  } else if (f_test) {
    if (r.r_squared) {
      out += ", \u03b7\u00b2 = " + apa_r(*r.r_squared);  // eta squared = R^2
      out += ci(r.eta_squared_low, r.eta_squared_high, [](double v) { return apa_r(v); });
    }
  } else if (!f_test && !chi2 && t != "tost") {
    if (r.cohen_d) {
      // A paired test's d is d_z (the mean difference over the differences' sd): named so.
      out += std::string(r.test == "paired_t" ? ", d_z = " : ", d = ") + apa_two_dec(*r.cohen_d) +
             ci(r.cohen_d_low, r.cohen_d_high, [](double v) { return apa_two_dec(v); });
    }
    if (r.log_bf10) out += ", " + bayes_factor_text(*r.log_bf10);
  }
  return out;
}

std::string apa_bayes_factor(double log_bf10) { return bayes_factor_text(log_bf10); }

// ---------------------------------------------------------------------------------------------
// Labels

std::optional<double> decision_p(const stats::TestResult& result) noexcept {
  return result.p_adjusted ? result.p_adjusted : result.p_value;
}

std::string inference_label(const stats::TestResult& difference, double alpha,
                            std::string_view lhs, std::string_view rhs,
                            const stats::TestResult* tost) {
  const auto p = decision_p(difference);
  if (!difference.computed || !p) return std::string(kNotComputable);
  if (*p < alpha) {
    const double effect = difference.estimate.value_or(0.0) - difference.mu.value_or(0.0);
    return fmt::format("{}{}{}", lhs, effect > 0 ? ">" : "<", rhs);
  }
  if (difference.log_bf10 && -*difference.log_bf10 >= std::log(kBf01Equivalence)) {
    return fmt::format("{}{}{}", lhs, kApprox, rhs);
  }
  if (tost == nullptr) return std::string(kNotSignificant);
  const auto tp = decision_p(*tost);
  if (!tost->computed || !tp) return std::string(kNotComputable);
  return *tp < alpha ? fmt::format("{}{}{}", lhs, kApprox, rhs) : std::string(kNotSignificant);
}

std::string one_sample_label(const stats::TestResult& difference, double alpha,
                             const stats::TestResult* tost) {
  return inference_label(difference, alpha, "M", "R", tost);
}

std::string two_sample_label(const stats::TestResult& difference, double alpha,
                             const stats::TestResult* tost) {
  return inference_label(difference, alpha, "A", "B", tost);
}

}  // namespace feint::tables
