// exposure_counts(): see feint/models/exposure.hpp.
#include "feint/models/exposure.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::models {

std::vector<double> exposure_counts(std::span<const std::string> participant,
                                    std::span<const double> iteration,
                                    std::span<const std::string> strategy) {
  const std::size_t n = participant.size();
  if (iteration.size() != n || strategy.size() != n)
    throw std::invalid_argument("exposure_counts: columns of different lengths");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (participant[a] != participant[b]) return participant[a] < participant[b];
    return iteration[a] < iteration[b];
  });
  std::vector<double> out(n, 0.0);
  std::map<std::pair<std::string, std::string>, double> seen;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    if (k > 0 && participant[order[k - 1]] == participant[i] &&
        iteration[order[k - 1]] == iteration[i])
      throw InvalidData(fmt::format(
          "participant {} has two trials at iteration {} (a participant in more than one condition?): "
          "the exposure to a strategy counts a participant's earlier trials, so it needs one trial per "
          "participant and iteration, as in a between-participants design",
          participant[i], iteration[i]));
    double& count = seen[{participant[i], strategy[i]}];
    out[i] = count;
    count += 1;
  }
  return out;
}

}  // namespace feint::models

// ------------------------------------------------------------------------------------------------
// exposure_slopes_by_condition(): see feint/models/exposure.hpp.

#include <cmath>
#include <set>

#include <fmt/format.h>

#include "feint/stats/bayes_factor.hpp"
#include "feint/stats/effect_size.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::models {

namespace {

/// The OLS slope of y on x (centred sums, so a constant added to y changes nothing); NaN with fewer
/// than 2 points or fewer than 2 distinct x.
double ols_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2) return std::nan("");
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  bool distinct = false;
  for (std::size_t i = 1; i < n && !distinct; ++i) distinct = x[i] != x[0];
  return distinct && sxx > 0 ? sxy / sxx : std::nan("");
}

std::string left_out_text(std::size_t left_out) {
  if (left_out == 0) return "";
  return fmt::format("{} participant{} left out (fewer than 2 trials with a value at 2 distinct exposures)",
                     left_out, left_out == 1 ? "" : "s");
}

constexpr const char* kSlopeMethod =
    "exposure slope: mean of the participants' OLS slopes, one-sample t test (two-stage)";
constexpr const char* kDifferenceMethod =
    "difference of exposure slopes between conditions: Welch two-sample t test on the participants' "
    "OLS slopes (two-stage)";
constexpr const char* kPairedDifferenceMethod =
    "difference of exposure slopes between conditions within participants: paired t test on each "
    "participant's two OLS slopes (two-stage)";

/// Each participant's OLS exposure slope per (condition, strategy), row-major with the strategy
/// fastest, and how many participants of each had no slope.
struct ParticipantSlopes {
  std::vector<std::vector<double>> slopes;
  std::vector<std::vector<std::string>> who;  // the participant of each slope
  std::vector<std::size_t> left_out;
};

// Stage 1: each participant's trials of each strategy (condition, strategy, participant), then
// their slopes.
ParticipantSlopes participant_slopes(std::span<const std::string> participant,
                                     std::span<const std::string> condition,
                                     std::span<const std::string> strategy,
                                     std::span<const double> exposure, std::span<const double> y,
                                     const std::vector<std::string>& conditions,
                                     const std::vector<std::string>& strategies) {
  struct Trials {
    std::vector<double> x, y;
  };
  std::map<std::tuple<std::string, std::string, std::string>, Trials> cells;
  for (std::size_t i = 0; i < participant.size(); ++i) {
    Trials& c = cells[{condition[i], strategy[i], participant[i]}];  // seen, even without a value
    if (!std::isfinite(y[i]) || !std::isfinite(exposure[i])) continue;
    c.x.push_back(exposure[i]);
    c.y.push_back(y[i]);
  }
  ParticipantSlopes out;
  out.slopes.resize(conditions.size() * strategies.size());
  out.who.resize(out.slopes.size());
  out.left_out.assign(out.slopes.size(), 0);
  for (std::size_t c = 0; c < conditions.size(); ++c)
    for (std::size_t s = 0; s < strategies.size(); ++s) {
      auto it = cells.lower_bound({conditions[c], strategies[s], std::string()});
      for (; it != cells.end() && std::get<0>(it->first) == conditions[c] && std::get<1>(it->first) == strategies[s];
           ++it) {
        const double b = ols_slope(it->second.x, it->second.y);
        if (std::isfinite(b)) {
          out.slopes[c * strategies.size() + s].push_back(b);
          out.who[c * strategies.size() + s].push_back(std::get<2>(it->first));
        } else
          ++out.left_out[c * strategies.size() + s];
      }
    }
  return out;
}

// Stage 2: one strategy's mean slope in one condition.
ExposureSlope mean_slope(const std::string& strategy, const std::string& condition,
                         const std::vector<double>& b, std::size_t left_out,
                         const stats::TestOptions& options) {
  ExposureSlope sl;
  sl.strategy = strategy;
  sl.condition = condition;
  sl.participants = b.size();
  sl.left_out = left_out;
  const std::string lo = left_out_text(left_out);
  if (b.size() < 2) {
    sl.test = stats::TestResult::not_computable(
        "one_sample_t", kSlopeMethod,
        fmt::format(
            "fewer than 2 participants with an exposure slope of strategy '{}' in condition '{}' "
            "(n = {}){}",
            strategy, condition, b.size(), lo.empty() ? "" : "; " + lo));
  } else {
    sl.test = stats::t_test_one_sample(b, 0.0, options);
    sl.test.method = kSlopeMethod;
    if (sl.test.computed && sl.test.sd1)
      sl.std_error = *sl.test.sd1 / std::sqrt(static_cast<double>(b.size()));
    if (!lo.empty()) sl.test.note = sl.test.note.empty() ? lo : sl.test.note + "; " + lo;
  }
  return sl;
}

// The difference of strategy s between the first two conditions: Welch on the participants' slopes.
ExposureSlope slope_difference(std::size_t s, const std::vector<std::string>& strategies,
                               const std::vector<std::string>& conditions,
                               const ParticipantSlopes& ps, const stats::TestOptions& options,
                               double bf_prior_r) {
  const auto& slopes = ps.slopes;
  const std::size_t ka = s, kb = strategies.size() + s;
  ExposureSlope dif;
  dif.strategy = strategies[s];
  dif.condition = conditions[0] + "-" + conditions[1];
  dif.participants = slopes[ka].size() + slopes[kb].size();
  dif.left_out = ps.left_out[ka] + ps.left_out[kb];
  if (slopes[ka].size() < 2 || slopes[kb].size() < 2) {
    dif.test = stats::TestResult::not_computable(
        "welch_t", kDifferenceMethod,
        fmt::format(
            "fewer than 2 participants with an exposure slope of strategy '{}' in condition '{}' "
            "(n = {})",
            strategies[s], slopes[ka].size() < 2 ? conditions[0] : conditions[1],
            std::min(slopes[ka].size(), slopes[kb].size())));
    return dif;
  }
  // As every Welch row of the report (report/table1.cpp): d with its interval, and the BF.
  dif.test = stats::t_test_welch(slopes[ka], slopes[kb], options);
  stats::add_effect_size_intervals(dif.test);
  stats::add_bayes_factor(dif.test, bf_prior_r);
  dif.test.method = kDifferenceMethod;
  if (dif.test.computed && dif.test.sd1 && dif.test.sd2) {
    const double va = *dif.test.sd1 * *dif.test.sd1 / static_cast<double>(slopes[ka].size());
    const double vb = *dif.test.sd2 * *dif.test.sd2 / static_cast<double>(slopes[kb].size());
    dif.std_error = std::sqrt(va + vb);
  }
  const std::string lo = left_out_text(dif.left_out);
  if (!lo.empty()) dif.test.note = dif.test.note.empty() ? lo : dif.test.note + "; " + lo;
  return dif;
}

// Within participants: strategy s's slopes of the participants with a slope in both of the first
// two conditions, paired (slopes[k] are sorted by participant), then a paired t test with d_z and
// the one-sample form of the Bayes factor.
ExposureSlope paired_slope_difference(std::size_t s, const std::vector<std::string>& strategies,
                                      const std::vector<std::string>& conditions, const ParticipantSlopes& ps,
                                      const stats::TestOptions& options, double bf_prior_r) {
  const std::size_t ka = s, kb = strategies.size() + s;
  std::vector<double> a, b;
  for (std::size_t i = 0, j = 0; i < ps.who[ka].size() && j < ps.who[kb].size();) {
    if (ps.who[ka][i] < ps.who[kb][j]) {
      ++i;
    } else if (ps.who[kb][j] < ps.who[ka][i]) {
      ++j;
    } else {
      a.push_back(ps.slopes[ka][i++]);
      b.push_back(ps.slopes[kb][j++]);
    }
  }
  ExposureSlope dif;
  dif.strategy = strategies[s];
  dif.condition = conditions[0] + "-" + conditions[1];
  dif.participants = a.size();
  // Participants with a slope in one condition only cannot be paired: they are left out too.
  dif.left_out = ps.slopes[ka].size() + ps.slopes[kb].size() - 2 * a.size() + ps.left_out[ka] + ps.left_out[kb];
  if (a.size() < 2) {
    dif.test = stats::TestResult::not_computable(
        "paired_t", kPairedDifferenceMethod,
        fmt::format("fewer than 2 participants with an exposure slope of strategy '{}' in both conditions (n = {})",
                    strategies[s], a.size()));
    return dif;
  }
  dif.test = stats::t_test_paired(a, b, options);
  stats::add_effect_size_intervals(dif.test);
  stats::add_bayes_factor(dif.test, bf_prior_r);
  dif.test.method = kPairedDifferenceMethod;
  // SE of the mean difference, sd(a - b) / sqrt(n) (the test's sd1 and sd2 describe a and b).
  double m = 0, ss = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m += (a[i] - b[i]) / static_cast<double>(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) ss += (a[i] - b[i] - m) * (a[i] - b[i] - m);
  if (dif.test.computed) dif.std_error = std::sqrt(ss / static_cast<double>(a.size() - 1) / static_cast<double>(a.size()));
  const std::string lo = dif.left_out == 0 ? std::string()
                                           : fmt::format("{} participant{} without a slope in both conditions left out",
                                                         dif.left_out, dif.left_out == 1 ? "" : "s");
  if (!lo.empty()) dif.test.note = dif.test.note.empty() ? lo : dif.test.note + "; " + lo;
  return dif;
}

}  // namespace

ExposureByCondition exposure_slopes_by_condition(std::span<const std::string> participant,
                                                 std::span<const std::string> condition,
                                                 std::span<const std::string> strategy,
                                                 std::span<const double> exposure,
                                                 std::span<const double> y,
                                                 std::vector<std::string> conditions,
                                                 double conf_level, double bf_prior_r, bool paired) {
  const std::size_t n = participant.size();
  if (condition.size() != n || strategy.size() != n || exposure.size() != n || y.size() != n)
    throw std::invalid_argument("exposure_slopes_by_condition: columns of different lengths");
  if (conditions.empty()) {
    const std::set<std::string> s(condition.begin(), condition.end());
    conditions.assign(s.begin(), s.end());
  }
  const std::set<std::string> strategy_set(strategy.begin(), strategy.end());
  const std::vector<std::string> strategies(strategy_set.begin(), strategy_set.end());
  stats::TestOptions options;
  options.conf_level = conf_level;

  const ParticipantSlopes ps =
      participant_slopes(participant, condition, strategy, exposure, y, conditions, strategies);
  ExposureByCondition out;
  for (std::size_t c = 0; c < conditions.size(); ++c)
    for (std::size_t s = 0; s < strategies.size(); ++s) {
      const std::size_t k = c * strategies.size() + s;
      out.slopes.push_back(
          mean_slope(strategies[s], conditions[c], ps.slopes[k], ps.left_out[k], options));
    }
  if (conditions.size() < 2) return out;
  for (std::size_t s = 0; s < strategies.size(); ++s)
    out.differences.push_back(paired ? paired_slope_difference(s, strategies, conditions, ps, options, bf_prior_r)
                                     : slope_difference(s, strategies, conditions, ps, options, bf_prior_r));
  return out;
}

}  // namespace feint::models
