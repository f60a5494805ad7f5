// Estimated marginal means and contrasts of a mixed model (see feint/models/emmeans.hpp).
#include "feint/models/emmeans.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <map>
#include <tuple>
#include <numbers>
#include <optional>
#include <vector>

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

// The reference grid: G conditions x K iterations; a mean or contrast is a weight vector w over
// the cells (index g * K + j), tested by `test` (the model's SE and df for w).
struct Grid {
  std::vector<std::string> groups, times;  // times as text ("3")
  std::string time_name = "iteration";
  std::function<EmmRow(const std::string&, const std::string&, const Eigen::VectorXd&, double)> test;
  std::size_t G() const { return groups.size(); }
  std::size_t K() const { return times.size(); }
};

struct Mean {
  std::string label;
  Eigen::VectorXd w;
};

std::vector<Mean> condition_means(const Grid& grid, std::optional<std::size_t> at_time) {
  std::vector<Mean> out;
  for (std::size_t g = 0; g < grid.G(); ++g) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(grid.G() * grid.K()));
    for (std::size_t j = 0; j < grid.K(); ++j)
      if (!at_time || *at_time == j)
        w(static_cast<Eigen::Index>(g * grid.K() + j)) = at_time ? 1.0 : 1.0 / static_cast<double>(grid.K());
    out.push_back({grid.groups[g], w});
  }
  return out;
}

std::vector<Mean> iteration_means(const Grid& grid, std::optional<std::size_t> in_group) {
  std::vector<Mean> out;
  for (std::size_t j = 0; j < grid.K(); ++j) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(grid.G() * grid.K()));
    for (std::size_t g = 0; g < grid.G(); ++g)
      if (!in_group || *in_group == g)
        w(static_cast<Eigen::Index>(g * grid.K() + j)) =
            in_group ? 1.0 : 1.0 / static_cast<double>(grid.G());
    out.push_back({grid.time_name + grid.times[j], w});
  }
  return out;
}

EmmRow t_row(const std::string& label, const std::string& by, double est, double var, double df,
             double conf_level) {
  EmmRow r;
  r.label = label;
  r.by = by;
  r.estimate = est;
  if (!(var > 0) || !(df > 0) || !std::isfinite(df)) {
    r.computed = false;
    r.note = "variance or df not positive";
    return r;
  }
  r.std_error = std::sqrt(var);
  r.df = df;
  r.statistic = est / r.std_error;
  const double q = detail::t_quantile_upper((1 - conf_level) / 2, df);
  r.conf_low = est - q * r.std_error;
  r.conf_high = est + q * r.std_error;
  // Two-sided p from Student's t: P(|T| > |t|) = 2 (1 - F(|t|)); via the quantile helper's
  // distribution would need Boost here too.
  r.p_value = detail::t_two_sided_p(r.statistic, df);
  r.p_unadjusted = r.p_value;
  return r;
}

Grid model_grid(const MixedModelFit& fit) {
  require_grid(fit);
  Grid grid;
  grid.groups = fit.group_levels;
  for (const double t : fit.time_levels) grid.times.push_back(level_text(t));
  grid.time_name = fit.spec.time;
  // The design rows of the G x K cells, once per grid (a family has up to hundreds of contrasts).
  const std::size_t K = fit.time_levels.size();
  auto rows = std::make_shared<std::vector<Eigen::VectorXd>>();
  for (std::size_t c = 0; c < grid.G() * K; ++c)
    rows->push_back(fit.cell_row(c / K, fit.time_levels[c % K]));
  grid.test = [&fit, rows](const std::string& label, const std::string& by,
                           const Eigen::VectorXd& w, double conf_level) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    for (Eigen::Index c = 0; c < w.size(); ++c)
      if (w(c) != 0) L += w(c) * (*rows)[static_cast<std::size_t>(c)];
    EmmRow r;
    r.label = label;
    r.by = by;
    const Contrast ct = contrast(fit, L, conf_level);
    r.estimate = L.dot(fit.beta);
    if (!ct.test.computed) {
      r.computed = false;
      r.note = ct.test.note;
      return r;
    }
    r.std_error = ct.std_error;
    r.df = *ct.test.df;
    r.statistic = *ct.test.statistic;
    r.p_value = *ct.test.p_value;
    r.p_unadjusted = r.p_value;
    r.conf_low = *ct.test.conf_low;
    r.conf_high = *ct.test.conf_high;
    return r;
  };
  return grid;
}

// The multivariate model of the repeated-measures ANOVA (emmeans on an afex object, its default
// "multivariate"): cell means, covariance of the iterations pooled within conditions
// S = E / (N - a), var(w) = sum_g w_g' S w_g / n_g, df = N - a.
Grid anova_grid(const WideDesign& d) {
  Grid grid;
  grid.groups = d.conditions;
  for (const long long it : d.iterations) grid.times.push_back(fmt::format("{}", it));
  const auto G = static_cast<Eigen::Index>(d.conditions.size());
  const auto K = static_cast<Eigen::Index>(d.k());
  const std::vector<std::size_t> n = d.group_sizes();
  auto means = std::make_shared<Eigen::MatrixXd>(Eigen::MatrixXd::Zero(G, K));
  for (std::size_t i = 0; i < d.n(); ++i)
    for (Eigen::Index j = 0; j < K; ++j)
      (*means)(static_cast<Eigen::Index>(d.group[i]), j) += d.at(i, static_cast<std::size_t>(j));
  for (Eigen::Index g = 0; g < G; ++g) means->row(g) /= static_cast<double>(n[static_cast<std::size_t>(g)]);
  auto S = std::make_shared<Eigen::MatrixXd>(Eigen::MatrixXd::Zero(K, K));
  for (std::size_t i = 0; i < d.n(); ++i) {
    Eigen::VectorXd r(K);
    for (Eigen::Index j = 0; j < K; ++j)
      r(j) = d.at(i, static_cast<std::size_t>(j)) - (*means)(static_cast<Eigen::Index>(d.group[i]), j);
    *S += r * r.transpose();
  }
  const double df = static_cast<double>(d.n()) - static_cast<double>(G);
  *S /= df;
  grid.test = [means, S, n, G, K, df](const std::string& label, const std::string& by,
                                      const Eigen::VectorXd& w, double conf_level) {
    double est = 0, var = 0;
    for (Eigen::Index g = 0; g < G; ++g) {
      const Eigen::VectorXd wg = w.segment(g * K, K);
      est += wg.dot(means->row(g).transpose());
      var += wg.dot(*S * wg) / static_cast<double>(n[static_cast<std::size_t>(g)]);
    }
    return t_row(label, by, est, var, df, conf_level);
  };
  return grid;
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
  // Two means: the range of two is sqrt(2) |t|, so Tukey is the t test itself (exactly).
  if (n_means == 2) return;
  // qtukey per (conf, k, df): contrasts share k and nearly share df; df is rounded to 10
  // significant digits for the cache (its effect on the quantile is below 1e-10).
  thread_local std::map<std::tuple<double, double, double>, double> q_cache;
  for (std::size_t i = first; i < rows.size(); ++i) {
    EmmRow& r = rows[i];
    if (!r.computed) continue;
    r.p_value = ptukey_upper(std::abs(r.statistic) * std::numbers::sqrt2, k, r.df);
    const double key = std::stod(fmt::format("{:.10g}", r.df));
    auto it = q_cache.find({conf_level, k, key});
    if (it == q_cache.end()) it = q_cache.emplace(std::make_tuple(conf_level, k, key), qtukey(conf_level, k, key)).first;
    const double q = it->second / std::numbers::sqrt2;
    r.conf_low = r.estimate - q * r.std_error;
    r.conf_high = r.estimate + q * r.std_error;
  }
}

void pairwise(const Grid& grid, const std::vector<Mean>& means, const std::string& by,
              EmmAdjust adjust, double conf_level, std::vector<EmmRow>& out) {
  const std::size_t first = out.size();
  for (std::size_t i = 0; i < means.size(); ++i)
    for (std::size_t j = i + 1; j < means.size(); ++j)
      out.push_back(grid.test(means[i].label + " - " + means[j].label, by,
                              means[i].w - means[j].w, conf_level));
  adjust_family(out, first, adjust, means.size(), conf_level);
}

void poly(const Grid& grid, const std::vector<Mean>& means, const std::string& by,
          EmmAdjust adjust, double conf_level, std::vector<EmmRow>& out) {
  static const char* const names[] = {"linear", "quadratic", "cubic", "quartic"};
  const auto C = poly_contrasts(means.size());
  const std::size_t first = out.size();
  for (std::size_t d = 0; d < C.size(); ++d) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(means[0].w.size());
    for (std::size_t j = 0; j < means.size(); ++j) w += C[d][j] * means[j].w;
    out.push_back(grid.test(d < 4 ? names[d] : fmt::format("degree {}", d + 1), by, w,
                            conf_level));
  }
  adjust_family(out, first, adjust, means.size(), conf_level);
}


std::vector<EmmRow> grid_means(const Grid& grid, EmmTerm term, double conf_level) {
  std::vector<EmmRow> out;
  switch (term) {
    case EmmTerm::cells:
      for (std::size_t j = 0; j < grid.K(); ++j)
        for (const auto& m : condition_means(grid, j))
          out.push_back(grid.test(m.label + "|" + grid.times[j], "", m.w, conf_level));
      break;
    case EmmTerm::condition:
      for (const auto& m : condition_means(grid, std::nullopt))
        out.push_back(grid.test(m.label, "", m.w, conf_level));
      break;
    case EmmTerm::iteration: {
      const auto ms = iteration_means(grid, std::nullopt);
      for (std::size_t j = 0; j < grid.K(); ++j)
        out.push_back(grid.test(grid.times[j], "", ms[j].w, conf_level));
      break;
    }
  }
  return out;
}

std::vector<EmmRow> grid_contrasts(const Grid& grid, EmmFamily family, EmmAdjust adjust,
                                   double conf_level) {
  const bool is_poly = family == EmmFamily::poly_iteration || family == EmmFamily::poly_in_condition;
  if (is_poly && adjust == EmmAdjust::tukey)
    throw UsageError("--adjust tukey applies to pairwise contrasts, not to polynomial ones");
  const bool needs_groups = family == EmmFamily::pairwise_condition ||
                            family == EmmFamily::condition_at_iteration;
  if (needs_groups && grid.G() < 2)
    throw UsageError("contrasts of conditions need at least two conditions");
  std::vector<EmmRow> out;
  switch (family) {
    case EmmFamily::pairwise_condition:
      pairwise(grid, condition_means(grid, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::pairwise_iteration:
      pairwise(grid, iteration_means(grid, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::condition_at_iteration:
      for (std::size_t j = 0; j < grid.K(); ++j)
        pairwise(grid, condition_means(grid, j), grid.times[j], adjust, conf_level, out);
      break;
    case EmmFamily::iteration_in_condition:
      for (std::size_t g = 0; g < grid.G(); ++g)
        pairwise(grid, iteration_means(grid, g), grid.groups[g], adjust, conf_level, out);
      break;
    case EmmFamily::poly_iteration:
      poly(grid, iteration_means(grid, std::nullopt), "", adjust, conf_level, out);
      break;
    case EmmFamily::poly_in_condition:
      for (std::size_t g = 0; g < grid.G(); ++g)
        poly(grid, iteration_means(grid, g), grid.groups[g], adjust, conf_level, out);
      break;
  }
  return out;
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

DdfMethod parse_ddf_method(const std::string& text) {
  if (text == "satterthwaite") return DdfMethod::satterthwaite;
  if (text == "kenward-roger") return DdfMethod::kenward_roger;
  throw UsageError("--ddf " + text + ": expected satterthwaite or kenward-roger");
}

EmmContrastRequest parse_emm_contrasts(const std::vector<std::string>& contrasts,
                                       const std::string& adjust) {
  EmmContrastRequest r;
  for (const auto& c : contrasts) {
    using F = EmmFamily;
    std::vector<F> add;
    if (c == "pairwise") {
      add = {F::pairwise_condition, F::pairwise_iteration};
    } else if (c == "simple") {
      add = {F::condition_at_iteration, F::iteration_in_condition};
    } else if (c == "poly") {
      add = {F::poly_iteration, F::poly_in_condition};
    } else {
      throw UsageError("--contrasts " + c + ": expected pairwise, simple or poly");
    }
    for (const F f : add)
      if (std::find(r.families.begin(), r.families.end(), f) == r.families.end())
        r.families.push_back(f);
  }
  if (!adjust.empty()) {
    if (contrasts.empty()) throw UsageError("--adjust applies to --contrasts");
    r.adjust = parse_emm_adjust(adjust);
    if (*r.adjust == EmmAdjust::tukey &&
        std::find(contrasts.begin(), contrasts.end(), "poly") != contrasts.end())
      throw UsageError("--adjust tukey applies to pairwise and simple contrasts, not to poly");
  }
  return r;
}

std::vector<EmmRow> estimated_means(const MixedModelFit& fit, EmmTerm term, double conf_level) {
  return grid_means(model_grid(fit), term, conf_level);
}

std::vector<EmmRow> emm_contrasts(const MixedModelFit& fit, EmmFamily family, EmmAdjust adjust,
                                  double conf_level) {
  return grid_contrasts(model_grid(fit), family, adjust, conf_level);
}

std::vector<EmmRow> estimated_means(const WideDesign& design, EmmTerm term, double conf_level) {
  return grid_means(anova_grid(design), term, conf_level);
}

std::vector<EmmRow> emm_contrasts(const WideDesign& design, EmmFamily family, EmmAdjust adjust,
                                  double conf_level) {
  return grid_contrasts(anova_grid(design), family, adjust, conf_level);
}

}  // namespace feint::models
