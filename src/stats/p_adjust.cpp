#include "feint/stats/p_adjust.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::stats {

PAdjustMethod parse_p_adjust(std::string_view name) {
  if (name == "none") return PAdjustMethod::none;
  if (name == "bonferroni") return PAdjustMethod::bonferroni;
  if (name == "holm") return PAdjustMethod::holm;
  if (name == "hochberg") return PAdjustMethod::hochberg;
  if (name == "hommel") return PAdjustMethod::hommel;
  if (name == "BH" || name == "fdr") return PAdjustMethod::BH;
  if (name == "BY") return PAdjustMethod::BY;
  throw UsageError(fmt::format(
      "p-value adjustment '{}': expected none, bonferroni, holm, hochberg, hommel, BH (fdr) or BY",
      name));
}

std::string_view to_string(PAdjustMethod method) noexcept {
  switch (method) {
    case PAdjustMethod::bonferroni: return "bonferroni";
    case PAdjustMethod::holm: return "holm";
    case PAdjustMethod::hochberg: return "hochberg";
    case PAdjustMethod::hommel: return "hommel";
    case PAdjustMethod::BH: return "BH";
    case PAdjustMethod::BY: return "BY";
    case PAdjustMethod::none: break;
  }
  return "none";
}

namespace {

// R's order(p) / order(p, decreasing = TRUE): a stable sort of the indices.
std::vector<std::size_t> order(const std::vector<double>& p, bool decreasing) {
  std::vector<std::size_t> o(p.size());
  std::iota(o.begin(), o.end(), std::size_t{0});
  std::stable_sort(o.begin(), o.end(), [&](std::size_t a, std::size_t b) {
    return decreasing ? p[a] > p[b] : p[a] < p[b];
  });
  return o;
}

// The body of R's stats::p.adjust (R 4.2) for the non-missing values, transcribed step by step.
std::vector<double> adjust(std::vector<double> p, PAdjustMethod method) {
  const std::size_t n = p.size();
  const double nd = static_cast<double>(n);
  if (n <= 1) return p;
  if (n == 2 && method == PAdjustMethod::hommel) method = PAdjustMethod::hochberg;
  std::vector<double> out(n);
  switch (method) {
    case PAdjustMethod::none: return p;
    case PAdjustMethod::bonferroni:
      for (std::size_t i = 0; i < n; ++i) out[i] = std::min(1.0, nd * p[i]);
      return out;
    case PAdjustMethod::holm: {
      // pmin(1, cummax((n - i + 1) * p[o]))[ro], i = 1..n
      const auto o = order(p, false);
      double run = 0;
      for (std::size_t k = 0; k < n; ++k) {
        run = std::max(run, static_cast<double>(n - k) * p[o[k]]);
        out[o[k]] = std::min(1.0, run);
      }
      return out;
    }
    case PAdjustMethod::hochberg:
    case PAdjustMethod::BH:
    case PAdjustMethod::BY: {
      // i = n:1, o = order(p, decreasing = TRUE); pmin(1, cummin(factor(i) * p[o]))[ro]
      double q = 1;
      if (method == PAdjustMethod::BY) {
        q = 0;
        for (std::size_t k = 1; k <= n; ++k) q += 1.0 / static_cast<double>(k);
      }
      const auto o = order(p, true);
      double run = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < n; ++k) {
        const double i = static_cast<double>(n - k);
        double v = 0;
        if (method == PAdjustMethod::hochberg) v = (nd - i + 1) * p[o[k]];
        else if (method == PAdjustMethod::BH) v = nd / i * p[o[k]];
        else v = q * nd / i * p[o[k]];
        run = std::min(run, v);
        out[o[k]] = std::min(1.0, run);
      }
      return out;
    }
    case PAdjustMethod::hommel: {
      const auto o = order(p, false);
      std::vector<double> ps(n);
      for (std::size_t k = 0; k < n; ++k) ps[k] = p[o[k]];
      // q <- pa <- rep(min(n p / i), n)
      double m0 = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < n; ++k) m0 = std::min(m0, nd * ps[k] / static_cast<double>(k + 1));
      std::vector<double> q(n, m0), pa(n, m0);
      for (std::size_t m = n - 1; m >= 2; --m) {
        // i1 = 1..(n - m + 1), i2 = (n - m + 2)..n (1-based)
        const std::size_t n1 = n - m + 1;
        double q1 = std::numeric_limits<double>::infinity();
        for (std::size_t k = n1; k < n; ++k)  // i2, divided by 2..m
          q1 = std::min(q1, static_cast<double>(m) * ps[k] / static_cast<double>(k - n1 + 2));
        for (std::size_t k = 0; k < n1; ++k) q[k] = std::min(static_cast<double>(m) * ps[k], q1);
        for (std::size_t k = n1; k < n; ++k) q[k] = q[n1 - 1];
        for (std::size_t k = 0; k < n; ++k) pa[k] = std::max(pa[k], q[k]);
      }
      for (std::size_t k = 0; k < n; ++k) out[o[k]] = std::max(pa[k], ps[k]);
      return out;
    }
  }
  return p;
}

}  // namespace

std::vector<std::optional<double>> p_adjust(std::span<const std::optional<double>> p,
                                            PAdjustMethod method) {
  std::vector<double> present;
  for (const auto& v : p)
    if (v && !std::isnan(*v)) present.push_back(*v);
  const std::vector<double> adjusted = adjust(std::move(present), method);
  std::vector<std::optional<double>> out(p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i] && !std::isnan(*p[i])) out[i] = adjusted[k++];
  return out;
}

}  // namespace feint::stats
