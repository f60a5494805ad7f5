// Cronbach's alpha, reproducing psych::alpha()'s raw_alpha and alpha.drop.
#include "feint/stats/reliability.hpp"

#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::stats {
namespace {

// Raw alpha of the items `use` (indices into the covariance matrix c, order k x k).
double raw_alpha(const std::vector<double>& c, std::size_t k, const std::vector<std::size_t>& use) {
  double trace = 0.0;
  double total = 0.0;
  for (std::size_t a : use) {
    trace += c[a * k + a];
    for (std::size_t b : use) total += c[a * k + b];
  }
  const double m = static_cast<double>(use.size());
  return (1.0 - trace / total) * (m / (m - 1.0));
}

// Why the items cannot give an alpha at all (fewer than 2, or of different lengths); empty if they
// can.
std::string unusable_items(std::span<const std::vector<double>> items) {
  const std::size_t k = items.size();
  if (k < 2) return fmt::format("{} item(s): Cronbach's alpha needs at least 2", k);
  const std::size_t rows = items[0].size();
  for (std::size_t j = 1; j < k; ++j)
    if (items[j].size() != rows)
      return fmt::format("items have different lengths ({} and {} answers)", rows, items[j].size());
  return {};
}

// Complete cases: the covariance matrix c (k x k) over the respondents who answered every item.
// Sets out.n; false (out.note says why) when fewer than 2 did.
bool complete_case_covariance(std::span<const std::vector<double>> items, std::vector<double>& c,
                              CronbachAlpha& out) {
  const std::size_t k = items.size();
  const std::size_t rows = items[0].size();
  std::vector<std::size_t> complete;
  for (std::size_t i = 0; i < rows; ++i) {
    bool ok = true;
    for (const auto& item : items) ok = ok && !std::isnan(item[i]);
    if (ok) complete.push_back(i);
  }
  out.n = complete.size();
  if (out.n < 2) {
    out.note = fmt::format("{} respondent(s) answered every item: at least 2 are needed", out.n);
    return false;
  }
  // Two passes (means, then centred cross products) for accuracy.
  const double nd = static_cast<double>(out.n);
  std::vector<double> mean(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    double s = 0.0;
    for (std::size_t i : complete) s += items[j][i];
    mean[j] = s / nd;
  }
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a; b < k; ++b) {
      double s = 0.0;
      for (std::size_t i : complete) s += (items[a][i] - mean[a]) * (items[b][i] - mean[b]);
      c[a * k + b] = c[b * k + a] = s / (nd - 1.0);
    }
  return true;
}

// Pairwise-complete covariances, as R's cov(x, use = "pairwise"): for each pair, the means and the
// cross products over the respondents who answered both (two passes). Sets out.n (respondents who
// answered any item); false (out.note says why) when a pair was answered together by fewer than 2.
bool pairwise_covariance(std::span<const std::vector<double>> items, std::vector<double>& c,
                         CronbachAlpha& out) {
  const std::size_t k = items.size();
  const std::size_t rows = items[0].size();
  for (std::size_t i = 0; i < rows; ++i) {
    bool any = false;
    for (const auto& item : items) any = any || !std::isnan(item[i]);
    if (any) ++out.n;
  }
  for (std::size_t a = 0; a < k; ++a)
    for (std::size_t b = a; b < k; ++b) {
      double sa = 0.0, sb = 0.0;
      std::size_t n_ab = 0;
      for (std::size_t i = 0; i < rows; ++i) {
        if (std::isnan(items[a][i]) || std::isnan(items[b][i])) continue;
        sa += items[a][i];
        sb += items[b][i];
        ++n_ab;
      }
      if (n_ab < 2) {
        out.note = a == b ? fmt::format("item {} has {} answer(s): at least 2 are needed", a + 1,
                                        n_ab)
                          : fmt::format("items {} and {} were answered together by {} "
                                        "respondent(s): a pairwise covariance needs at least 2",
                                        a + 1, b + 1, n_ab);
        return false;
      }
      const double nd = static_cast<double>(n_ab), ma = sa / nd, mb = sb / nd;
      double s = 0.0;
      for (std::size_t i = 0; i < rows; ++i) {
        if (std::isnan(items[a][i]) || std::isnan(items[b][i])) continue;
        s += (items[a][i] - ma) * (items[b][i] - mb);
      }
      c[a * k + b] = c[b * k + a] = s / (nd - 1.0);
    }
  return true;
}

// The items with variance: psych deletes the others (with a warning) before computing alpha, so
// out.note names them.
std::vector<std::size_t> items_with_variance(const std::vector<double>& c, std::size_t k,
                                             CronbachAlpha& out) {
  std::vector<std::size_t> use;
  std::string constant;
  for (std::size_t j = 0; j < k; ++j) {
    if (c[j * k + j] > 0.0) {
      use.push_back(j);
    } else {
      constant += fmt::format("{}{}", constant.empty() ? "" : ", ", j + 1);
    }
  }
  out.items_used = use.size();
  if (!constant.empty())
    out.note = fmt::format("item(s) {} have no variance and were left out (as psych::alpha does)", constant);
  return use;
}

// out.if_dropped: the alpha of the items `use` without each one in turn.
void fill_if_dropped(const std::vector<double>& c, std::size_t k,
                     const std::vector<std::size_t>& use, CronbachAlpha& out) {
  if (use.size() == 2) {
    // psych's special case for two items: "alpha if dropped" is the regression-like C12 / C_jj
    // of the remaining item j.
    const std::size_t a = use[0], b = use[1];
    const double cov = c[a * k + b];
    if (c[b * k + b] > 0.0) out.if_dropped[a] = cov / c[b * k + b];
    if (c[a * k + a] > 0.0) out.if_dropped[b] = cov / c[a * k + a];
    return;
  }
  for (std::size_t drop : use) {
    std::vector<std::size_t> rest;
    for (std::size_t j : use)
      if (j != drop) rest.push_back(j);
    double rest_total = 0.0;
    for (std::size_t a : rest)
      for (std::size_t b : rest) rest_total += c[a * k + b];
    if (rest_total > 0.0) out.if_dropped[drop] = raw_alpha(c, k, rest);
  }
}

}  // namespace

AlphaMissing parse_alpha_missing(std::string_view text) {
  if (text == "pairwise") return AlphaMissing::pairwise;
  if (text == "complete" || text == "complete-cases") return AlphaMissing::complete_cases;
  throw UsageError(fmt::format("--alpha-missing '{}': expected pairwise (psych::alpha's default) "
                               "or complete (complete cases)",
                               text));
}

std::string_view to_string(AlphaMissing method) noexcept {
  return method == AlphaMissing::pairwise ? "pairwise" : "complete";
}

CronbachAlpha cronbach_alpha(std::span<const std::vector<double>> items, AlphaMissing missing) {
  CronbachAlpha out;
  out.missing = missing;
  const std::size_t k = items.size();
  out.if_dropped.assign(k, std::nullopt);
  out.note = unusable_items(items);
  if (!out.note.empty()) return out;

  std::vector<double> c(k * k, 0.0);
  const bool covariance_ok = missing == AlphaMissing::complete_cases
                                 ? complete_case_covariance(items, c, out)
                                 : pairwise_covariance(items, c, out);
  if (!covariance_ok) return out;

  const std::vector<std::size_t> use = items_with_variance(c, k, out);
  auto add_note = [&](const std::string& text) {
    out.note += out.note.empty() ? text : "; " + text;
  };
  if (use.size() < 2) {
    add_note(fmt::format("{} item(s) with variance: Cronbach's alpha needs at least 2", use.size()));
    return out;
  }
  double total_var = 0.0;
  for (std::size_t a : use)
    for (std::size_t b : use) total_var += c[a * k + b];
  if (!(total_var > 0.0)) {
    add_note("the total score has no variance (items cancel out): alpha is undefined");
    return out;
  }
  out.raw_alpha = raw_alpha(c, k, use);
  fill_if_dropped(c, k, use, out);
  return out;
}

}  // namespace feint::stats
