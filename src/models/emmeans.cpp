// Estimated marginal means and contrasts of a mixed model (see feint/models/emmeans.hpp).
#include "feint/models/emmeans.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "feint/error.hpp"
#include "feint/models/studentized_range.hpp"
#include "feint/stats/p_adjust.hpp"
#include "mixed_model_detail.hpp"

namespace feint::models {

namespace {

void require_grid(const MixedModelFit& fit) {
  if (fit.spec.time_scale != TimeScale::factor)
    throw UsageError(
        "estimated marginal means and their contrasts need iteration as a factor (not --trend "
        "or --exposure)");
}

std::string level_text(double v) { return fmt::format("{}", v); }

struct Mean {
  std::string label;
  Eigen::VectorXd L;
};

// The means of one family: cells restricted to a by-level, or marginal means.
std::vector<Mean> condition_means(const MixedModelFit& fit, std::optional<std::size_t> at_time) {
  std::vector<Mean> out;
  for (std::size_t g = 0; g < fit.group_levels.size(); ++g) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    if (at_time) {
      L = fit.cell_row(g, fit.time_levels[*at_time]);
    } else {
      for (const double t : fit.time_levels) L += fit.cell_row(g, t);
      L /= static_cast<double>(fit.time_levels.size());
    }
    out.push_back({fit.group_levels[g], L});
  }
  return out;
}

std::vector<Mean> iteration_means(const MixedModelFit& fit, std::optional<std::size_t> in_group) {
  std::vector<Mean> out;
  for (const double t : fit.time_levels) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    if (in_group) {
      L = fit.cell_row(*in_group, t);
    } else {
      for (std::size_t g = 0; g < fit.group_levels.size(); ++g) L += fit.cell_row(g, t);
      L /= static_cast<double>(fit.group_levels.size());
    }
    out.push_back({fit.spec.time + level_text(t), L});
  }
  return out;
}

EmmRow test_row(const MixedModelFit& fit, const std::string& label, const std::string& by,
                const Eigen::VectorXd& L, double conf_level) {
  EmmRow r;
  r.label = label;
  r.by = by;
  const Contrast c = contrast(fit, L, conf_level);
  r.estimate = L.dot(fit.beta);
  if (!c.test.computed) {
    r.computed = false;
    r.note = c.test.note;
    return r;
  }
  r.std_error = c.std_error;
  r.df = *c.test.df;
  r.statistic = *c.test.statistic;
  r.p_value = *c.test.p_value;
  r.p_unadjusted = r.p_value;
  r.conf_low = *c.test.conf_low;
  r.conf_high = *c.test.conf_high;
  return r;
}

// Applies `adjust` to one family (rows of one by-group) of pairwise or other contrasts among
// `n_means` means.
void adjust_family(std::vector<EmmRow>& rows, std::size_t first, EmmAdjust adjust,
                   std::size_t n_means, double conf_level) {
  const std::size_t m = rows.size() - first;
  if (adjust == EmmAdjust::none || m == 0) return;
  if (adjust == EmmAdjust::holm) {
    std::vector<std::optional<double>> ps;
    for (std::size_t i = first; i < rows.size(); ++i)
      ps.push_back(rows[i].computed ? std::optional<double>(rows[i].p_value) : std::nullopt);
    const auto adj = stats::p_adjust(ps, stats::PAdjustMethod::holm);
    for (std::size_t i = first; i < rows.size(); ++i) {
      EmmRow& r = rows[i];
      if (!r.computed) continue;
      r.p_value = *adj[i - first];
      // Bonferroni intervals (emmeans: Holm has none).
      const double q = detail::t_quantile_upper((1 - conf_level) / (2 * static_cast<double>(m)), r.df);
      r.conf_low = r.estimate - q * r.std_error;
      r.conf_high = r.estimate + q * r.std_error;
    }
    return;
  }
  const double k = static_cast<double>(n_means);
  // qtukey per (k, df): contrasts of one family share k and nearly share df; df is rounded to 10
  // significant digits for the cache (its effect on the quantile is below 1e-10).
  std::map<double, double> q_of_df;
  for (std::size_t i = first; i < rows.size(); ++i) {
    EmmRow& r = rows[i];
    if (!r.computed) continue;
    r.p_value = 1 - ptukey(std::abs(r.statistic) * std::numbers::sqrt2, k, r.df);
    const double key = std::stod(fmt::format("{:.10g}", r.df));
    auto it = q_of_df.find(key);
    if (it == q_of_df.end()) it = q_of_df.emplace(key, qtukey(conf_level, k, key)).first;
    const double q = it->second / std::numbers::sqrt2;
    r.conf_low = r.estimate - q * r.std_error;
    r.conf_high = r.estimate + q * r.std_error;
  }
}

void pairwise(const MixedModelFit& fit, const std::vector<Mean>& means, const std::string& by,
              EmmAdjust adjust, double conf_level, std::vector<EmmRow>& out) {
  const std::size_t first = out.size();
  for (std::size_t i = 0; i < means.size(); ++i)
    for (std::size_t j = i + 1; j < means.size(); ++j)
      out.push_back(test_row(fit, means[i].label + " - " + means[j].label, by,
                             means[i].L - means[j].L, conf_level));
  adjust_family(out, first, adjust, means.size(), conf_level);
}

void poly(const MixedModelFit& fit, const std::vector<Mean>& means, const std::string& by,
          EmmAdjust adjust, double conf_level, std::vector<EmmRow>& out) {
  static const char* const names[] = {"linear", "quadratic", "cubic", "quartic"};
  const auto C = poly_contrasts(means.size());
  const std::size_t first = out.size();
  for (std::size_t d = 0; d < C.size(); ++d) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    for (std::size_t j = 0; j < means.size(); ++j) L += C[d][j] * means[j].L;
    out.push_back(test_row(fit, d < 4 ? names[d] : fmt::format("degree {}", d + 1), by, L,
                           conf_level));
  }
  adjust_family(out, first, adjust, means.size(), conf_level);
}

}  // namespace

std::vector<std::vector<double>> poly_contrasts(std::size_t k) {
  // Orthonormal polynomials of 1..k (R's poly(seq_len(k), degree)) by Gram-Schmidt on powers of
  // the centred scores, then emmeans' integer scaling.
  const std::size_t degree = std::min<std::size_t>(6, k - 1);
  std::vector<Eigen::VectorXd> basis;
  const double centre = (static_cast<double>(k) + 1) / 2;
  Eigen::VectorXd x(static_cast<Eigen::Index>(k));
  for (std::size_t j = 0; j < k; ++j) x(static_cast<Eigen::Index>(j)) = static_cast<double>(j + 1) - centre;
  basis.push_back(Eigen::VectorXd::Ones(static_cast<Eigen::Index>(k)).normalized());
  std::vector<std::vector<double>> out;
  for (std::size_t d = 1; d <= degree; ++d) {
    Eigen::VectorXd v = x.array().pow(static_cast<double>(d));
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& b : basis) v -= v.dot(b) * b;
    v.normalize();
    basis.push_back(v);
    // emmeans' poly.emmc: divide by the smallest entry above .01, rescale until near-integers.
    double mn = 1e300;
    for (Eigen::Index j = 0; j < v.size(); ++j)
      if (v(j) > 0.01) mn = std::min(mn, v(j));
    Eigen::VectorXd c = v / mn;
    auto off = [&] { return (c.array() - c.array().round()).abs().maxCoeff(); };
    for (double z = off(); z > 0.05; z = off()) c /= z;
    std::vector<double> row;
    for (Eigen::Index j = 0; j < c.size(); ++j) row.push_back(std::round(c(j)));
    out.push_back(row);
  }
  return out;
}

std::string to_string(EmmFamily family) {
  switch (family) {
    case EmmFamily::pairwise_condition: return "pairwise ~ condition";
    case EmmFamily::pairwise_iteration: return "pairwise ~ iteration";
    case EmmFamily::condition_at_iteration: return "pairwise ~ condition | iteration";
    case EmmFamily::iteration_in_condition: return "pairwise ~ iteration | condition";
    case EmmFamily::poly_iteration: return "poly ~ iteration";
    case EmmFamily::poly_in_condition: return "poly ~ iteration | condition";
  }
  return "";
}

std::string to_string(EmmTerm term) {
  switch (term) {
    case EmmTerm::cells: return "condition:iteration";
    case EmmTerm::condition: return "condition";
    case EmmTerm::iteration: return "iteration";
  }
  return "";
}

std::string to_string(EmmAdjust adjust) {
  switch (adjust) {
    case EmmAdjust::none: return "none";
    case EmmAdjust::holm: return "holm";
    case EmmAdjust::tukey: return "tukey";
  }
  return "";
}

EmmAdjust parse_emm_adjust(const std::string& text) {
  if (text == "none") return EmmAdjust::none;
  if (text == "holm") return EmmAdjust::holm;
  if (text == "tukey") return EmmAdjust::tukey;
  throw UsageError("--adjust " + text + ": expected tukey, holm or none");
}

std::vector<EmmRow> estimated_means(const MixedModelFit& fit, EmmTerm term, double conf_level) {
  require_grid(fit);
  std::vector<EmmRow> out;
  switch (term) {
    case EmmTerm::cells:
      for (std::size_t j = 0; j < fit.time_levels.size(); ++j)
        for (const auto& m : condition_means(fit, j))
          out.push_back(test_row(fit, m.label + "|" + level_text(fit.time_levels[j]), "", m.L,
                                 conf_level));
      break;
    case EmmTerm::condition:
      for (const auto& m : condition_means(fit, std::nullopt))
        out.push_back(test_row(fit, m.label, "", m.L, conf_level));
      break;
    case EmmTerm::iteration:
      for (std::size_t j = 0; j < fit.time_levels.size(); ++j)
        out.push_back(test_row(fit, level_text(fit.time_levels[j]), "",
                               iteration_means(fit, std::nullopt)[j].L, conf_level));
      break;
  }
  return out;
}

std::vector<EmmRow> emm_contrasts(const MixedModelFit& fit, EmmFamily family, EmmAdjust adjust,
                                  double conf_level) {
  require_grid(fit);
  const bool is_poly = family == EmmFamily::poly_iteration || family == EmmFamily::poly_in_condition;
  if (is_poly && adjust == EmmAdjust::tukey)
    throw UsageError("--adjust tukey applies to pairwise contrasts, not to polynomial ones");
  const bool needs_groups = family == EmmFamily::pairwise_condition ||
                            family == EmmFamily::condition_at_iteration;
  if (needs_groups && fit.group_levels.size() < 2)
    throw UsageError("contrasts of conditions need at least two conditions");
  std::vector<EmmRow> out;
  switch (family) {
    case EmmFamily::pairwise_condition:
      pairwise(fit, condition_means(fit, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::pairwise_iteration:
      pairwise(fit, iteration_means(fit, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::condition_at_iteration:
      for (std::size_t j = 0; j < fit.time_levels.size(); ++j)
        pairwise(fit, condition_means(fit, j), level_text(fit.time_levels[j]), adjust, conf_level,
                 out);
      break;
    case EmmFamily::iteration_in_condition:
      for (std::size_t g = 0; g < fit.group_levels.size(); ++g)
        pairwise(fit, iteration_means(fit, g), fit.group_levels[g], adjust, conf_level, out);
      break;
    case EmmFamily::poly_iteration:
      poly(fit, iteration_means(fit, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::poly_in_condition:
      for (std::size_t g = 0; g < fit.group_levels.size(); ++g)
        poly(fit, iteration_means(fit, g), fit.group_levels[g], adjust, conf_level, out);
      break;
  }
  return out;
}

}  // namespace feint::models
