// The whole study's observer fit: per participant, pooled per condition, agreement and learning
// (feint/models/observer_fit.hpp, docs/observer.md). The single fit is in observer_fit.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/rank_tests.hpp"
#include "feint/stats/ttest.hpp"
#include "observer_study_detail.hpp"

namespace feint::models {

namespace {

using detail::observer::AgreementCells;
using detail::observer::count_exposure;
using detail::observer::without_unit;

/// Each participant's fitted observer, by (condition, participant).
using FittedObservers = std::map<std::pair<std::string, std::string>, GoalObserver>;

/// Labels every trial; returns the usable ones, naming each bad one in out.issues.
std::vector<ObservedTrial> usable_trials(std::vector<ObservedTrial>& trials,
                                         StudyObserverFit& out) {
  std::vector<ObservedTrial> good;
  good.reserve(trials.size());
  for (auto& tr : trials) {
    if (tr.label.empty()) {
      tr.label = tr.condition.empty() ? fmt::format("{}/{}", tr.participant, tr.iteration)
                                      : fmt::format("{}/{}/{}", tr.participant, tr.condition, tr.iteration);
    }
    if (auto why = trial_problem(tr)) {
      out.issues.push_back({tr.label, *why + "; the trial is left out of the fit"});
      continue;
    }
    good.push_back(std::move(tr));
  }
  return good;
}

/// Fits each participant (in each condition).
FittedObservers fit_participants(const std::vector<ObservedTrial>& good,
                                 const ObserverFitSettings& settings, StudyObserverFit& out) {
  FittedObservers fitted;
  for (std::size_t i = 0; i < good.size();) {
    std::size_t j = i;
    while (j < good.size() && good[j].participant == good[i].participant && good[j].condition == good[i].condition) ++j;
    const std::span<const ObservedTrial> part(good.data() + i, j - i);
    try {
      auto fit = fit_observer(part, settings, good[i].participant);
      for (const auto& n : fit.notes) out.issues.push_back({good[i].participant, without_unit(n, fit.unit)});
      fitted[{good[i].condition, good[i].participant}] = fit.observer();
      out.participants.push_back(std::move(fit));
    } catch (const Error& e) {
      out.issues.push_back({good[i].participant, fmt::format("the participant's fit failed: {}", e.what())});
    }
    i = j;
  }
  return fitted;
}

// The pooled maximum lies near the participants' fits: their mean, weighted by samples, is a
// start besides the grid.
std::optional<GoalObserver> pooled_start(const std::vector<ObserverFit>& participants,
                                         const std::string& condition) {
  double w = 0, beta = 0, tau = 0, logit = 0;
  for (const auto& f : participants) {
    if (f.condition != condition) continue;
    const auto n = static_cast<double>(f.samples);
    const GoalObserver o = f.observer();
    w += n;
    beta += n * o.beta;
    tau += n * o.tau;
    logit += n * (std::log(o.prior_right) - std::log1p(-o.prior_right));
  }
  if (w > 0) return GoalObserver{beta / w, tau / w, 1.0 / (1.0 + std::exp(-logit / w))};
  return std::nullopt;
}

/// The pooled fit of each condition, and its learning test.
void fit_conditions(const std::vector<ObservedTrial>& good, const ObserverFitSettings& settings,
                    StudyObserverFit& out) {
  for (std::size_t i = 0; i < good.size();) {
    std::size_t j = i;
    while (j < good.size() && good[j].condition == good[i].condition) ++j;
    const std::span<const ObservedTrial> cond(good.data() + i, j - i);
    const std::string name = good[i].condition.empty() ? "all" : good[i].condition;
    const std::optional<GoalObserver> start = pooled_start(out.participants, good[i].condition);
    try {
      auto fit = fit_observer(cond, settings, name, start);
      fit.condition = good[i].condition;
      for (const auto& n : fit.notes) out.issues.push_back({name, without_unit(n, name)});
      if (settings.learning) {
        const LearningTest lt = test_learning(cond, settings, fit);
        out.learning.push_back(lt);
      }
      out.conditions.push_back(std::move(fit));
    } catch (const Error& e) {
      out.issues.push_back({name, fmt::format("the pooled fit failed: {}", e.what())});
    }
    i = j;
  }
}

// The model's trace at each participant's fitted parameters against the pad, summed per cell.
AgreementCells agreement_cells(const std::vector<ObservedTrial>& good, const FittedObservers& fitted,
                               const ObserverFitSettings& settings, StudyObserverFit& out) {
  AgreementCells cells;
  for (const auto& tr : good) {
    const auto it = fitted.find({tr.condition, tr.participant});
    if (it == fitted.end()) continue;
    const auto model = belief_trace(tr.path, tr.times, settings.goals, it->second);
    const double target = tr.goal == GoalSide::right ? 1.0 : 0.0;
    const double v = tr.pad_speed.value_or(settings.pad_speed);
    metrics::TrialScore hs, ms;
    try {
      hs = metrics::score_trace(tr.times, tr.pads, target, v, settings.metric);
      ms = metrics::score_trace(tr.times, model, target, v, settings.metric);
    } catch (const Error& e) {
      out.issues.push_back({tr.label, fmt::format("left out of the agreement tables: {}", e.what())});
      continue;
    }
    cells.add(tr.condition, tr.strategy, tr.iteration,
              {hs.error, ms.error, hs.confusion, ms.confusion, tr.pads, model});
  }
  return cells;
}

}  // namespace

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A participant's estimate on the comparison's scale: log beta (a rate; its difference is the log
// of a ratio), tau as it is. NaN for beta = 0 (no log: a participant who never infers).
double comparison_value(const ObserverFit& f, const std::string& parameter) {
  const auto& p = f.parameter(parameter);
  return parameter == "beta" ? std::log(p.estimate) : p.estimate;
}

bool at_range_bound(const ParameterEstimate& p) {
  return (p.conf_low == p.estimate && p.low_at_bound) || (p.conf_high == p.estimate && p.high_at_bound);
}

// True when some participant was fitted in both conditions: the design is within participants.
bool fitted_in_both(std::span<const ObserverFit> participants, const std::string& a, const std::string& b) {
  std::map<std::string, int> seen;
  for (const auto& f : participants) {
    if (f.condition == a) seen[f.unit] |= 1;
    if (f.condition == b) seen[f.unit] |= 2;
  }
  return std::any_of(seen.begin(), seen.end(), [](const auto& s) { return s.second == 3; });
}

// Within participants: each participant's two estimates paired (paired t with d_z and the
// one-sample JZS Bayes factor, Wilcoxon signed-rank with the matched-pairs r_rb); participants
// fitted in one condition only are left out and counted in the note.
bool compare_paired(ObserverComparison& c, std::span<const ObserverFit> participants, const std::string& parameter,
                    const stats::TestOptions& options) {
  std::map<std::string, std::array<double, 2>> pairs;
  for (const auto& f : participants) {
    if (f.condition != c.condition_a && f.condition != c.condition_b) continue;
    const auto it = pairs.try_emplace(f.unit, std::array<double, 2>{kNaN, kNaN}).first;
    it->second[f.condition == c.condition_a ? 0 : 1] = comparison_value(f, parameter);
    if (at_range_bound(f.parameter(parameter))) ++c.at_bound;
  }
  std::vector<double> xa, xb, diff;
  std::size_t lone = 0;
  for (const auto& [who, v] : pairs) {
    if (!std::isfinite(v[0]) || !std::isfinite(v[1])) {
      ++lone;
      continue;
    }
    xa.push_back(v[0]);
    xb.push_back(v[1]);
    diff.push_back(v[0] - v[1]);
  }
  if (xa.size() < 2) return false;
  c.paired = true;
  c.welch = stats::t_test_paired(xa, xb, options);
  stats::add_effect_size_intervals(c.welch);
  stats::add_bayes_factor(c.welch);
  c.rank = stats::wilcoxon_signed_rank(diff, 0.0, options);
  const auto nonzero = static_cast<std::size_t>(std::count_if(diff.begin(), diff.end(), [](double d) { return d != 0; }));
  stats::add_effect_size_intervals(c.rank, nonzero);
  if (lone > 0) {
    const std::string note = fmt::format("{} participant(s) without an estimate in both conditions left out", lone);
    for (auto* t : {&c.welch, &c.rank}) t->note += (t->note.empty() ? "" : "; ") + note;
  }
  return true;
}

// Between participants: the two groups of participants' estimates (Welch t with d and the JZS
// Bayes factor, Mann-Whitney with r_rb).
bool compare_independent(ObserverComparison& c, std::span<const ObserverFit> participants,
                         const std::string& parameter, const stats::TestOptions& options) {
  std::vector<double> xa, xb;
  for (const auto& f : participants) {
    if (f.condition != c.condition_a && f.condition != c.condition_b) continue;
    const double v = comparison_value(f, parameter);
    if (!std::isfinite(v)) continue;
    (f.condition == c.condition_a ? xa : xb).push_back(v);
    // An estimate on the range's edge (tau = 0, beta at --beta-max) is kept but counted.
    if (at_range_bound(f.parameter(parameter))) ++c.at_bound;
  }
  if (xa.size() < 2 || xb.size() < 2) return false;
  c.welch = stats::t_test_welch(xa, xb, options);
  stats::add_effect_size_intervals(c.welch);
  stats::add_bayes_factor(c.welch);
  c.rank = stats::mann_whitney(xa, xb, options);
  stats::add_effect_size_intervals(c.rank);
  return true;
}

}  // namespace

std::vector<ObserverComparison> compare_conditions(std::span<const ObserverFit> participants,
                                                   const std::string& a, const std::string& b,
                                                   double level) {
  std::vector<ObserverComparison> out;
  const bool within = fitted_in_both(participants, a, b);
  const stats::TestOptions options{stats::Alternative::two_sided, level};
  for (const std::string parameter : {"beta", "tau"}) {
    ObserverComparison c{parameter == "beta" ? "log beta" : "tau", a, b, {}, {}, 0};
    const bool done = within ? compare_paired(c, participants, parameter, options)
                             : compare_independent(c, participants, parameter, options);
    if (!done) return {};
    out.push_back(std::move(c));
  }
  return out;
}

StudyObserverFit fit_study(std::vector<ObservedTrial> trials, const ObserverFitSettings& settings) {
  settings.validate();
  StudyObserverFit out;
  // 1. Check every trial; a bad one is named and left out.
  std::vector<ObservedTrial> good = usable_trials(trials, out);
  // 2. Exposure: earlier trials of the same strategy by the same participant (by iteration).
  count_exposure(good);
  out.trials_used = good.size();
  // 3. Per participant.
  const auto fitted = fit_participants(good, settings, out);
  // 4. Pooled per condition (and the learning test).
  fit_conditions(good, settings, out);
  if (out.conditions.size() == 2)
    out.comparisons = compare_conditions(out.participants, out.conditions[0].condition,
                                         out.conditions[1].condition, settings.level);
  // 5. Agreement: the model's trace at each participant's fitted parameters against the pad.
  out.agreement = agreement_cells(good, fitted, settings, out).rows();
  return out;
}

}  // namespace feint::models
