// fit_mixed_model(): design (treatment coding as R), REML fit, lmerTest's Satterthwaite machinery
// and type-III hypotheses. The tests of a fitted model (contrast(), contrast_md()) are in
// mixed_model_tests.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "feint/error.hpp"
#include "feint/models/mixed_model.hpp"
#include "mixed_model_detail.hpp"

namespace feint::models {

namespace {

// A model term: its variables (0 = group, 1 = time), and its columns in X.
struct Term {
  std::string name;
  std::set<int> vars;
  bool numeric = false;  ///< involves the numeric time covariate
  std::vector<Eigen::Index> cols;
};

std::string level_text(double v) { return fmt::format("{}", v); }

struct Layout {
  std::vector<Term> terms;
  std::vector<std::string> coef_names;
  std::size_t n_group = 1, n_time = 1;  // levels (n_time = 1 column for a linear time)
  bool has_group = false;
  bool linear = false;
};

Layout make_layout(const MixedModelFit& fit) {
  Layout lay;
  lay.linear = fit.spec.time_scale == TimeScale::linear;
  lay.n_group = fit.group_levels.size();
  lay.has_group = lay.n_group > 1;
  lay.coef_names.push_back("(Intercept)");
  Eigen::Index col = 1;
  Term g{fit.spec.group, {0}, false, {}};
  if (lay.has_group) {
    for (std::size_t k = 1; k < lay.n_group; ++k) {
      lay.coef_names.push_back(fit.spec.group + fit.group_levels[k]);
      g.cols.push_back(col++);
    }
    lay.terms.push_back(g);
  }
  Term t{fit.spec.time, {1}, lay.linear, {}};
  if (lay.linear) {
    lay.coef_names.push_back(fit.spec.time);
    t.cols.push_back(col++);
  } else {
    for (std::size_t j = 1; j < fit.time_levels.size(); ++j) {
      lay.coef_names.push_back(fit.spec.time + level_text(fit.time_levels[j]));
      t.cols.push_back(col++);
    }
  }
  lay.terms.push_back(t);
  if (lay.has_group) {
    Term gt{fit.spec.group + ":" + fit.spec.time, {0, 1}, lay.linear, {}};
    const std::size_t nt = lay.linear ? 2 : fit.time_levels.size();
    for (std::size_t j = 1; j < nt; ++j) {
      for (std::size_t k = 1; k < lay.n_group; ++k) {
        lay.coef_names.push_back(lay.coef_names[g.cols[k - 1]] + ":" +
                                 lay.coef_names[t.cols[j - 1]]);
        gt.cols.push_back(col++);
      }
    }
    lay.terms.push_back(gt);
  }
  return lay;
}

// The rank-deficient "complete" design of lmerTest's get_rdX (treatment coding, every level),
// and for each column of X the index of the same-named column of it.
struct CompleteDesign {
  Eigen::MatrixXd rdX;
  std::vector<Eigen::Index> x_to_rd;
};

CompleteDesign complete_design(const MixedModelFit& fit, const Layout& lay,
                               const std::vector<std::size_t>& gi,
                               const std::vector<std::size_t>& ti, const Eigen::VectorXd& time) {
  const std::size_t C = lay.n_group, K = fit.time_levels.size();
  const Eigen::Index n = static_cast<Eigen::Index>(gi.size());
  std::vector<Eigen::VectorXd> cols;
  std::map<std::string, Eigen::Index> name_of;
  auto add = [&](const std::string& name, Eigen::VectorXd v) {
    name_of[name] = static_cast<Eigen::Index>(cols.size());
    cols.push_back(std::move(v));
  };
  add("(Intercept)", Eigen::VectorXd::Ones(n));
  auto indicator = [&](const std::vector<std::size_t>& idx, std::size_t level) {
    Eigen::VectorXd v(n);
    for (Eigen::Index r = 0; r < n; ++r) v(r) = idx[static_cast<std::size_t>(r)] == level ? 1 : 0;
    return v;
  };
  std::vector<std::string> gname(C), tname(K);
  for (std::size_t k = 0; k < C; ++k) gname[k] = fit.spec.group + fit.group_levels[k];
  if (lay.has_group)
    for (std::size_t k = 0; k < C; ++k) add(gname[k], indicator(gi, k));
  if (lay.linear) {
    add(fit.spec.time, time);
  } else {
    for (std::size_t j = 0; j < K; ++j) {
      tname[j] = fit.spec.time + level_text(fit.time_levels[j]);
      add(tname[j], indicator(ti, j));
    }
  }
  if (lay.has_group) {
    if (lay.linear) {
      for (std::size_t k = 0; k < C; ++k)
        add(gname[k] + ":" + fit.spec.time, indicator(gi, k).cwiseProduct(time));
    } else {
      for (std::size_t j = 0; j < K; ++j)
        for (std::size_t k = 0; k < C; ++k)
          add(gname[k] + ":" + tname[j], indicator(gi, k).cwiseProduct(indicator(ti, j)));
    }
  }
  CompleteDesign cd;
  cd.rdX.resize(n, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) cd.rdX.col(static_cast<Eigen::Index>(c)) = cols[c];
  for (const auto& name : lay.coef_names) cd.x_to_rd.push_back(name_of.at(name));
  return cd;
}

// Residuals of the least-squares fit of the columns of Y on the columns of A (lm.fit's resid).
Eigen::MatrixXd lsq_residuals(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Y) {
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  cod.setThreshold(1e-7);
  return Y - A * cod.solve(Y);
}

// lmerTest's get_contrasts_type3 (all factors in treatment coding) or, with one term,
// get_contrasts_type1.
std::vector<Eigen::MatrixXd> type3_hypotheses(const Layout& lay, const Eigen::MatrixXd& X,
                                              const CompleteDesign& cd) {
  const Eigen::Index p = X.cols();
  std::vector<Eigen::MatrixXd> out;
  if (p <= 1 || lay.terms.size() <= 1) {
    const Eigen::MatrixXd Lt = detail::doolittle_lower(X.transpose() * X).transpose();
    for (const auto& t : lay.terms) {
      Eigen::MatrixXd L(static_cast<Eigen::Index>(t.cols.size()), p);
      for (std::size_t r = 0; r < t.cols.size(); ++r)
        L.row(static_cast<Eigen::Index>(r)) = Lt.row(t.cols[r]);
      out.push_back(L);
    }
    return out;
  }
  Eigen::MatrixXd L =
      detail::zapsmall(X.colPivHouseholderQr().solve(cd.rdX).transpose());  // rd params x p
  // Containment (SAS): F1 in F2 when F2 has every variable of F1 and more, same covariates.
  auto contained_in = [&](const Term& a, const Term& b) {
    const bool subset = std::includes(b.vars.begin(), b.vars.end(), a.vars.begin(), a.vars.end());
    return subset && b.vars.size() > a.vars.size() && a.numeric == b.numeric;
  };
  std::vector<std::size_t> order(lay.terms.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return lay.terms[a].vars.size() > lay.terms[b].vars.size();
  });
  for (const std::size_t ti : order) {
    const Term& t = lay.terms[ti];
    std::vector<Eigen::Index> ccols;
    for (const auto& o : lay.terms)
      if (contained_in(t, o)) ccols.insert(ccols.end(), o.cols.begin(), o.cols.end());
    if (ccols.empty()) continue;
    Eigen::MatrixXd A(L.rows(), static_cast<Eigen::Index>(ccols.size()));
    for (std::size_t c = 0; c < ccols.size(); ++c)
      A.col(static_cast<Eigen::Index>(c)) = L.col(ccols[c]);
    Eigen::MatrixXd Y(L.rows(), static_cast<Eigen::Index>(t.cols.size()));
    for (std::size_t c = 0; c < t.cols.size(); ++c)
      Y.col(static_cast<Eigen::Index>(c)) = L.col(t.cols[c]);
    const Eigen::MatrixXd R = detail::zapsmall(lsq_residuals(A, Y));
    for (std::size_t c = 0; c < t.cols.size(); ++c)
      L.col(t.cols[c]) = R.col(static_cast<Eigen::Index>(c));
  }
  Eigen::MatrixXd Lsel(p, p);
  for (Eigen::Index r = 0; r < p; ++r) Lsel.row(r) = L.row(cd.x_to_rd[static_cast<std::size_t>(r)]);
  for (const auto& t : lay.terms) {
    std::vector<Eigen::VectorXd> rows;
    for (const auto c : t.cols) {
      const Eigen::VectorXd row = Lsel.col(c);
      if (row.cwiseAbs().sum() > 1e-8) rows.push_back(row);
    }
    Eigen::MatrixXd Lt(static_cast<Eigen::Index>(rows.size()), p);
    for (std::size_t r = 0; r < rows.size(); ++r) Lt.row(static_cast<Eigen::Index>(r)) = rows[r];
    out.push_back(Lt);
  }
  return out;
}

}  // namespace

namespace {

// The row of X for a cell, given the layout (made once per fit: make_layout formats names).
Eigen::VectorXd cell_row_of(const MixedModelFit& fit, const Layout& lay, std::size_t group_level,
                            double time) {
  const auto& time_levels = fit.time_levels;
  Eigen::VectorXd row = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(lay.coef_names.size()));
  row(0) = 1;
  const Term* g = lay.has_group ? &lay.terms[0] : nullptr;
  const Term& t = lay.terms[lay.has_group ? 1 : 0];
  if (g != nullptr && group_level > 0) row(g->cols[group_level - 1]) = 1;
  if (lay.linear) {
    row(t.cols[0]) = time;
    if (g != nullptr && group_level > 0) row(lay.terms[2].cols[group_level - 1]) = time;
  } else {
    const auto it = std::find(time_levels.begin(), time_levels.end(), time);
    if (it == time_levels.end()) throw std::invalid_argument("cell_row: unknown time level");
    const auto j = static_cast<std::size_t>(it - time_levels.begin());
    if (j > 0) row(t.cols[j - 1]) = 1;
    if (g != nullptr && group_level > 0 && j > 0)
      row(lay.terms[2].cols[(j - 1) * (lay.n_group - 1) + (group_level - 1)]) = 1;
  }
  return row;
}

}  // namespace

Eigen::VectorXd MixedModelFit::cell_row(std::size_t group_level, double time) const {
  return cell_row_of(*this, make_layout(*this), group_level, time);
}

namespace {

/// Each observation's group and time level (indices into fit.group_levels, fit.time_levels).
struct LevelIndex {
  std::vector<std::size_t> group, time;
};

/// The model's matrices, rows grouped by participant (stable: file order within a participant).
struct Design {
  Eigen::MatrixXd X, Z;
  Eigen::VectorXd y, time;
  std::vector<std::size_t> group, time_level;  ///< LevelIndex in the order of the rows
  std::vector<std::size_t> start;              ///< first row of each participant, then n
};

void check_columns(const LongData& data, const ModelSpec& spec) {
  const std::size_t n = data.y.size();
  if (data.participant.size() != n || data.group.size() != n || data.time.size() != n)
    throw std::invalid_argument("fit_mixed_model: columns of different lengths");
  if (spec.random_slope && spec.time_scale != TimeScale::linear)
    throw UsageError("a random slope needs a linear trend in " + spec.time + " (--trend)");
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(data.y[i]) || !std::isfinite(data.time[i]))
      throw InvalidData(fmt::format("{}: a value is not finite (participant {})", spec.response,
                                    data.participant[i]));
}

/// (1 + group | participant) needs the group within participants and excludes (1 + time | ...).
void check_random_group_slope(const ModelSpec& spec, bool group_between) {
  if (!spec.random_group_slope) return;
  if (group_between)
    throw UsageError(fmt::format(
        "a random slope of {} (1 + {} | {}) needs {} within participants: with {} between "
        "participants each participant has one {} and the slope is not identified",
        spec.group, spec.group, spec.participant, spec.group, spec.group, spec.group));
  if (spec.random_slope)
    throw UsageError(fmt::format(
        "random slopes of both {} and {} are not supported: use (1 + {} | {}) or (1 + {} | {})",
        spec.group, spec.time, spec.group, spec.participant, spec.time, spec.participant));
}

/// Fills fit.participants (first-appearance order) and returns each one's index in it.
std::map<std::string, std::size_t> index_participants(const LongData& data, const ModelSpec& spec,
                                                      bool group_between, MixedModelFit& fit) {
  const std::size_t n = data.y.size();
  std::map<std::string, std::size_t> pidx;
  std::map<std::string, std::string> group_of;
  for (std::size_t i = 0; i < n; ++i) {
    if (pidx.emplace(data.participant[i], fit.participants.size()).second)
      fit.participants.push_back(data.participant[i]);
    if (group_between) {
      auto [it, fresh] = group_of.emplace(data.participant[i], data.group[i]);
      if (!fresh && it->second != data.group[i])
        throw InvalidData(fmt::format(
            "participant {} is in two {}s ('{}' and '{}'): {} must be between participants",
            data.participant[i], spec.group, it->second, data.group[i], spec.group));
    }
  }
  if (fit.participants.size() < 2)
    throw InvalidData(fmt::format(
        "metric '{}': {} participant ({}): the mixed model needs at least 2 participants (the "
        "variance between participants cannot be estimated from one)",
        spec.response, fit.participants.size(), fit.participants.empty() ? "" : fit.participants[0]));
  return pidx;
}

/// fit.group_levels (as given, or sorted) and fit.time_levels (ascending), and each observation's.
LevelIndex index_levels(const LongData& data, const ModelSpec& spec, MixedModelFit& fit) {
  const std::size_t n = data.y.size();
  if (!spec.group_levels.empty()) {
    fit.group_levels = spec.group_levels;
  } else {
    std::set<std::string> s(data.group.begin(), data.group.end());
    fit.group_levels.assign(s.begin(), s.end());
  }
  {
    std::set<double> s(data.time.begin(), data.time.end());
    fit.time_levels.assign(s.begin(), s.end());
  }
  LevelIndex li{std::vector<std::size_t>(n), std::vector<std::size_t>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = std::find(fit.group_levels.begin(), fit.group_levels.end(), data.group[i]);
    if (it == fit.group_levels.end())
      throw InvalidData(
          fmt::format("{} '{}' is not one of the levels given", spec.group, data.group[i]));
    li.group[i] = static_cast<std::size_t>(it - fit.group_levels.begin());
    li.time[i] = static_cast<std::size_t>(
        std::lower_bound(fit.time_levels.begin(), fit.time_levels.end(), data.time[i]) -
        fit.time_levels.begin());
  }
  return li;
}

/// Refuses responses whose variance the model cannot split between participant and residual.
void check_variation(const LongData& data, const ModelSpec& spec, const MixedModelFit& fit) {
  const std::size_t n = data.y.size();
  {
    const double y0 = data.y[0];
    if (std::all_of(data.y.begin(), data.y.end(), [&](double v) { return v == y0; }))
      throw InvalidData(
          fmt::format("metric '{}' has no variance (every value is {}): the mixed "
                      "model cannot be fitted",
                      spec.response, y0));
  }
  // lme4's checks (check.nobs.vs.nlev, check.nobs.vs.nRE): with no participant observed twice,
  // or no more trials than random effects, the participant variance cannot be told apart from the
  // residual one (the REML criterion is flat along a line of (theta, sigma)).
  if (n <= fit.participants.size())
    throw InvalidData(fmt::format(
        "metric '{}': {} trials of {} participants: every participant has a single trial{}, so the "
        "variance between participants cannot be told apart from the residual variance; the mixed "
        "model needs participants with at least two trials{}",
        spec.response, n, fit.participants.size(),
        fit.time_levels.size() == 1 ? fmt::format(" (one {}, {})", spec.time,
                                                  level_text(fit.time_levels[0]))
                                    : "",
        fit.time_levels.size() == 1 && spec.time == "iteration"
            ? " (for a single iteration, compare the conditions with `feint table`)"
            : ""));
  // No variation within any participant: the residual variance is 0 and REML drives theta to
  // infinity (lme4 converges to a boundary with meaningless df); refuse, as the ANOVA does.
  std::map<std::string, std::pair<double, double>> range;
  for (std::size_t i = 0; i < n; ++i) {
    auto [it, fresh] = range.try_emplace(data.participant[i], data.y[i], data.y[i]);
    if (!fresh) {
      it->second.first = std::min(it->second.first, data.y[i]);
      it->second.second = std::max(it->second.second, data.y[i]);
    }
  }
  if (std::all_of(range.begin(), range.end(),
                  [](const auto& r) { return r.second.first == r.second.second; }))
    throw InvalidData(fmt::format(
        "metric '{}': no variation within any participant (each participant's trials all "
        "have the same value): the residual variance is 0 and the mixed model is degenerate",
        spec.response));
}

/// Refuses random slopes, groups or a time factor that the numbers of trials cannot identify.
void check_identifiable(const ModelSpec& spec, bool group_between, const MixedModelFit& fit,
                        std::size_t n) {
  const std::size_t q = fit.group_levels.size();
  if (spec.random_group_slope && n <= q * fit.participants.size())
    throw InvalidData(fmt::format(
        "metric '{}': {} trials of {} participants are not more than the {} random effects of "
        "(1 + {} | {}) ({} per participant, one per {}): the participant deviations per {} and "
        "the residual variance cannot all be estimated (as lme4's check of the number of "
        "observations against random effects); drop the random {} slope",
        spec.response, n, fit.participants.size(), q * fit.participants.size(), spec.group,
        spec.participant, q, spec.group, spec.group, spec.group));
  if (spec.random_slope && n <= 2 * fit.participants.size())
    throw InvalidData(fmt::format(
        "metric '{}': {} trials of {} participants are not more than the {} random effects of "
        "(1 + {} | {}): the random slopes and the residual variance cannot both be estimated; drop "
        "--random-slope",
        spec.response, n, fit.participants.size(), 2 * fit.participants.size(), spec.time,
        spec.participant));
  if (group_between && fit.group_levels.size() > 1 &&
      fit.participants.size() <= fit.group_levels.size())
    throw InvalidData(fmt::format(
        "metric '{}': {} participants in {} {}s: with one participant per {}, {} is confounded "
        "with participant (no participant variance left to test it against); the mixed model "
        "needs more participants than {}s",
        spec.response, fit.participants.size(), fit.group_levels.size(), spec.group, spec.group,
        spec.group, spec.group));
  if (spec.time_scale == TimeScale::factor && fit.time_levels.size() < 2)
    throw InvalidData(fmt::format(
        "metric '{}': one {} ({}): the model of {} as a factor needs at least two", spec.response,
        spec.time, level_text(fit.time_levels[0]), spec.time));
}

/// Refuses an empty group x time cell (time as a factor) and a trend through one time value.
void check_cells(const ModelSpec& spec, const MixedModelFit& fit, const Layout& lay,
                 const LevelIndex& li) {
  const std::size_t n = li.group.size();
  if (spec.time_scale == TimeScale::factor && lay.has_group) {
    std::vector<std::size_t> count(lay.n_group * fit.time_levels.size(), 0);
    for (std::size_t i = 0; i < n; ++i) ++count[li.time[i] * lay.n_group + li.group[i]];
    for (std::size_t j = 0; j < fit.time_levels.size(); ++j)
      for (std::size_t k = 0; k < lay.n_group; ++k)
        if (count[j * lay.n_group + k] == 0)
          throw InvalidData(fmt::format(
              "metric '{}': no observation of {} '{}' at {} {}: with {} as a factor every {} x {} "
              "cell needs data (the interaction is not estimable); drop that {}, or model {} as "
              "a linear trend (--trend)",
              spec.response, spec.group, fit.group_levels[k], spec.time,
              level_text(fit.time_levels[j]), spec.time, spec.group, spec.time, spec.time,
              spec.time));
  }
  if (spec.time_scale == TimeScale::linear && fit.time_levels.size() < 2)
    throw InvalidData(fmt::format("metric '{}': a trend in {} needs at least two distinct values",
                                  spec.response, spec.time));
}

/// The design, rows grouped by participant; fills fit.trials_per_participant.
Design build_design(const LongData& data, const ModelSpec& spec, MixedModelFit& fit,
                    const Layout& lay, std::map<std::string, std::size_t>& pidx,
                    const LevelIndex& li) {
  const std::size_t n = data.y.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pidx[data.participant[a]] < pidx[data.participant[b]];
  });
  const auto p = static_cast<Eigen::Index>(lay.coef_names.size());
  const Eigen::Index q = spec.random_group_slope ? static_cast<Eigen::Index>(lay.n_group)
                         : spec.random_slope      ? 2
                                                  : 1;
  Design des;
  des.X = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), p);
  des.Z.resize(static_cast<Eigen::Index>(n), q);
  des.y.resize(static_cast<Eigen::Index>(n));
  des.time.resize(static_cast<Eigen::Index>(n));
  des.group.resize(n);
  des.time_level.resize(n);
  des.start = {0};
  fit.trials_per_participant.assign(fit.participants.size(), 0);
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = order[r];
    const auto row = static_cast<Eigen::Index>(r);
    des.X.row(row) = cell_row_of(fit, lay, li.group[i], data.time[i]).transpose();
    des.Z(row, 0) = 1;
    if (spec.random_group_slope) {
      for (Eigen::Index k = 1; k < q; ++k)
        des.Z(row, k) = li.group[i] == static_cast<std::size_t>(k) ? 1 : 0;
    } else if (q == 2) {
      des.Z(row, 1) = data.time[i];
    }
    des.y(row) = data.y[i];
    des.time(row) = data.time[i];
    des.group[r] = li.group[i];
    des.time_level[r] = li.time[i];
    const std::size_t pi = pidx[data.participant[i]];
    ++fit.trials_per_participant[pi];
    if (r + 1 == n || pidx[data.participant[order[r + 1]]] != pi) des.start.push_back(r + 1);
  }
  return des;
}

void check_full_rank(const Eigen::MatrixXd& X, const ModelSpec& spec, std::size_t n) {
  const Eigen::Index p = X.cols();
  if (static_cast<Eigen::Index>(n) <= p)
    throw InvalidData(fmt::format(
        "metric '{}': {} trials cannot estimate {} fixed effects (and the residual variance)",
        spec.response, n, p));
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  qr.setThreshold(1e-9);
  if (qr.rank() < p)
    throw InvalidData(fmt::format(
        "metric '{}': the fixed-effects design is rank deficient (a {} x {} combination is "
        "confounded with another)",
        spec.response, spec.group, spec.time));
}

/// v * 2^(power * scale_exp): from the units of y / 2^scale_exp back to those of y (exact).
double up(double v, int power, int scale_exp) { return std::ldexp(v, power * scale_exp); }

/// sigma, beta, the REML criterion and vcov(beta) in the units of y, from the fit in those of
/// y / 2^scale_exp; returns sigma in the fit's units.
double store_estimates(MixedModelFit& fit, const detail::Problem& problem,
                       const detail::Evaluation& ev, int scale_exp) {
  const Eigen::Index p = problem.X.cols();
  const double nn = static_cast<double>(problem.X.rows()), pp = static_cast<double>(p);
  const double sigma_s = std::sqrt(ev.r2 / (nn - pp));  // in the units of ys
  fit.sigma = up(sigma_s, 1, scale_exp);
  fit.beta = ev.beta.unaryExpr([&](double v) { return up(v, 1, scale_exp); });
  // REMLcrit of y: (n - p) log(r2) gains (n - p) log(2^(2k)).
  fit.reml_criterion = problem.profiled_reml(fit.theta) +
                       (nn - pp) * 2.0 * static_cast<double>(scale_exp) * std::log(2.0);
  fit.vcov_beta = fit.sigma * fit.sigma * ev.xthx_chol.solve(Eigen::MatrixXd::Identity(p, p));
  return sigma_s;
}

/// lme4's VarCorr and isSingular from the relative covariance factor Lam.
void store_variance_components(MixedModelFit& fit, const Eigen::MatrixXd& Lam) {
  const Eigen::MatrixXd Sb = fit.sigma * fit.sigma * Lam * Lam.transpose();
  fit.variance.residual = fit.sigma * fit.sigma;
  fit.variance.participant = Sb(0, 0);
  fit.singular = Lam.diagonal().minCoeff() < 1e-4;  // lme4's isSingular(tol = 1e-4)
  if (fit.spec.random_slope) {
    fit.variance.slope = Sb(1, 1);
    if (Sb(0, 0) > 0 && Sb(1, 1) > 0)
      fit.variance.correlation = Sb(0, 1) / std::sqrt(Sb(0, 0) * Sb(1, 1));
  } else if (fit.spec.random_group_slope && Sb.rows() > 1) {
    // VarCorr's order: the variances of the dummies, then the correlations column-wise.
    const Eigen::Index q = Sb.rows();
    for (Eigen::Index k = 1; k < q; ++k) fit.variance.group_slopes.push_back(Sb(k, k));
    for (Eigen::Index j = 0; j < q; ++j)
      for (Eigen::Index i = j + 1; i < q; ++i)
        fit.variance.group_correlations.push_back(
            Sb(i, i) > 0 && Sb(j, j) > 0 ? Sb(i, j) / std::sqrt(Sb(i, i) * Sb(j, j))
                                         : std::numeric_limits<double>::quiet_NaN());
  } else {
    fit.variance.icc = Sb(0, 0) / (Sb(0, 0) + fit.variance.residual);
  }
}

// Satterthwaite (lmerTest's as_lmerModLT) with exact derivatives (lmerTest takes numDeriv's
// Richardson differences, whose absolute step ruins its df in small units), in a scale-free
// parametrisation: varpar = (theta, sigma) with sigma = u * sigma_hat at u = 1, where the
// positive-eigenvalue cut of the Hessian is made; then carried back to (theta, sigma).
void store_satterthwaite(MixedModelFit& fit, const detail::Problem& problem, double sigma_s,
                         int scale_exp) {
  const Eigen::Index nv = fit.theta.size() + 1;
  Eigen::VectorXd vp_s(nv);
  vp_s << fit.theta, sigma_s;
  detail::SatterthwaiteParts parts =
      detail::satterthwaite_parts(problem.reml_deviance_hessian(vp_s),
                                  problem.vcov_beta_jacobian(vp_s), sigma_s, fit.sigma, scale_exp);
  fit.varpar.resize(nv);
  fit.varpar << fit.theta, fit.sigma;
  fit.vcov_varpar = std::move(parts.vcov_varpar);
  fit.jac_vcov_beta = std::move(parts.jac_vcov_beta);
}

// In the units of ys (scale-free), then back: Phi_A scales by 2^(2k), P_r by 2^(-4k) and W by
// 2^(4k) (exact).
void store_kenward_roger(MixedModelFit& fit, const detail::Problem& problem,
                         const detail::Evaluation& ev, const Eigen::MatrixXd& Lam, double sigma_s,
                         int scale_exp) {
  const Eigen::Index p = problem.X.cols();
  const Eigen::MatrixXd Phi_s =
      sigma_s * sigma_s * ev.xthx_chol.solve(Eigen::MatrixXd::Identity(p, p));
  const detail::KenwardRogerParts kr = detail::kenward_roger_parts(
      problem, sigma_s * sigma_s * Lam * Lam.transpose(), sigma_s * sigma_s, Phi_s);
  fit.vcov_beta_adj = kr.phi_adj.unaryExpr([&](double v) { return up(v, 2, scale_exp); });
  for (const auto& P : kr.P)
    fit.kr_P.push_back(P.unaryExpr([&](double v) { return up(v, -4, scale_exp); }));
  fit.kr_W = kr.W.unaryExpr([&](double v) { return up(v, 4, scale_exp); });
}

// Type-III ANOVA.
void store_type3_anova(MixedModelFit& fit, const Layout& lay, const Design& des) {
  const CompleteDesign cd = complete_design(fit, lay, des.group, des.time_level, des.time);
  const std::vector<Eigen::MatrixXd> hyp = type3_hypotheses(lay, des.X, cd);
  for (std::size_t t = 0; t < lay.terms.size(); ++t) {
    AnovaTerm row = contrast_md(fit, hyp[t]);
    row.term = lay.terms[t].name;
    fit.anova.push_back(row);
  }
  fit.anova_hypotheses = hyp;
}

}  // namespace

MixedModelFit fit_mixed_model(const LongData& data, const ModelSpec& spec, bool group_between) {
  const std::size_t n = data.y.size();
  check_columns(data, spec);
  check_random_group_slope(spec, group_between);
  MixedModelFit fit;
  fit.spec = spec;
  fit.n_obs = n;
  std::map<std::string, std::size_t> pidx = index_participants(data, spec, group_between, fit);
  const LevelIndex li = index_levels(data, spec, fit);
  check_variation(data, spec, fit);
  check_identifiable(spec, group_between, fit, n);
  const Layout lay = make_layout(fit);
  check_cells(spec, fit, lay, li);
  const Design des = build_design(data, spec, fit, lay, pidx, li);
  check_full_rank(des.X, spec, n);
  fit.coef_names = lay.coef_names;

  // Scale invariance: the response is divided by a power of two near its spread, so that every
  // step below (optimiser, its tolerances, the eigenvalue cut) sees numbers of order 1 whatever the
  // unit of the response, and multiplying back is exact. y * 2^k gives bit-identical F, df and p.
  const int scale_exp = detail::response_scale_exponent(des.y);
  const Eigen::VectorXd ys = des.y.unaryExpr([&](double v) { return std::ldexp(v, -scale_exp); });
  detail::Problem problem(des.X, des.Z, ys, des.start);
  fit.theta = detail::optimise_theta(problem);
  const detail::Evaluation ev = problem.evaluate(fit.theta);
  const double sigma_s = store_estimates(fit, problem, ev, scale_exp);
  const Eigen::MatrixXd Lam = problem.lambda(fit.theta);
  store_variance_components(fit, Lam);
  store_satterthwaite(fit, problem, sigma_s, scale_exp);
  if (spec.ddf == DdfMethod::kenward_roger)
    store_kenward_roger(fit, problem, ev, Lam, sigma_s, scale_exp);
  store_type3_anova(fit, lay, des);
  return fit;
}

}  // namespace feint::models
