// Relabelling p-values of the random-intercept models' condition tests: see
// feint/models/model_relabelling.hpp. The refits themselves are in relabelling_refit.cpp.
#include "feint/models/model_relabelling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/stats/permutation.hpp"
#include "relabelling_general.hpp"
#include "relabelling_refit.hpp"

namespace feint::models {

namespace {

using detail::FactorModel;
using detail::Statistics;
using detail::TrendModel;

constexpr double kInf = std::numeric_limits<double>::infinity();

void check_arguments(const LongData& data, const std::vector<std::string>& group_levels,
                     const RelabellingOptions& options) {
  if (group_levels.size() < 2)
    throw UsageError(fmt::format("relabel_condition_tests: needs two or more conditions, got {}", group_levels.size()));
  if (options.permutations == 0) throw UsageError("relabel_condition_tests: permutations must be >= 1");
  const std::size_t n = data.y.size();
  if (data.participant.size() != n || data.group.size() != n || data.time.size() != n)
    throw UsageError("relabel_condition_tests: participant, group, time and y differ in length");
}

/// Participants in first-appearance order: each one's condition (1 = the second level), each
/// row's participant, and the participants of the second condition.
struct Membership {
  std::vector<char> in_b;
  std::vector<std::size_t> row_person;
  std::vector<std::size_t> members;
};

// Each participant must stay in one condition: relabelling moves whole participants.
Membership assign_participants(const LongData& data, const std::vector<std::string>& group_levels) {
  const std::size_t n = data.y.size();
  std::map<std::string, std::size_t> index;
  Membership m;
  m.row_person.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    int g = -1;
    if (data.group[r] == group_levels[0]) g = 0;
    else if (data.group[r] == group_levels[1]) g = 1;
    if (g < 0)
      throw InvalidData(fmt::format("participant {}: condition '{}' is neither '{}' nor '{}'", data.participant[r],
                                    data.group[r], group_levels[0], group_levels[1]));
    auto [it, added] = index.emplace(data.participant[r], m.in_b.size());
    if (added)
      m.in_b.push_back(static_cast<char>(g));
    else if (m.in_b[it->second] != g)
      throw InvalidData(fmt::format("participant {} has trials in both conditions ('{}' and '{}'): whole "
                                    "participants cannot be relabelled",
                                    data.participant[r], group_levels[0], group_levels[1]));
    m.row_person[r] = it->second;
  }
  for (std::size_t i = 0; i < m.in_b.size(); ++i)
    if (m.in_b[i]) m.members.push_back(i);
  if (m.members.empty() || m.members.size() == m.in_b.size())
    throw UsageError("relabel_condition_tests: both conditions need at least one participant");
  return m;
}


std::optional<double> magnitude(const std::optional<double>& t) {
  return t ? std::optional<double>(std::fabs(*t)) : std::nullopt;
}

// Test k's statistic: 0 the interaction F, 1 the condition F, 2 the slope difference's |t|.
std::optional<double> statistic(const Statistics& s, std::size_t k) {
  if (k == 0) return s.interaction_f;
  if (k == 1) return s.condition_f;
  return magnitude(s.slope_t);
}

/// One test's count: over every labelling (`exact`), or Besag & Clifford's sequential p-value over
/// the sampled ones.
struct Tally {
  double threshold = kInf;  // infinite: no observed statistic, no p-value
  std::uint64_t reached = 0, visited = 0;
  std::optional<stats::SequentialPValue> sampled;
  bool wanted() const { return std::isfinite(threshold) && !(sampled && sampled->done()); }
  void add(bool reaches) {
    if (sampled) {
      sampled->add(reaches);
    } else {
      ++visited;
      reached += reaches;
    }
  }
};

// Every relabelling's statistics against the observed ones; a relabelling whose statistic cannot
// be computed counts as reaching it (and as not computable). Sampled labellings are visited until
// every test's sequential p-value has stopped; a test that has stopped is no longer refitted.
void relabelling_p_values(FactorModel& factor, TrendModel& trend, const Membership& m,
                          const RelabellingOptions& options, const Statistics& observed,
                          RelabelledConditionTests& out) {
  const bool exact = stats::every_labelling(m.in_b.size(), m.members.size(), options.permutations);
  std::array<Tally, 3> tally;  // interaction, condition, slope difference
  for (std::size_t k = 0; k < 3; ++k) {
    tally[k].threshold = detail::relabelling_threshold(statistic(observed, k));
    if (!exact) tally[k].sampled.emplace(options.exceedances, options.permutations + 1);
  }
  std::vector<char> labels(m.in_b.size());
  bool observed_labelling = !exact;  // sampling visits it first; SequentialPValue counts it itself
  const stats::Labellings l = stats::for_each_labelling_while(
      m.in_b.size(), m.members, options.permutations, options.seed, [&](std::span<const std::size_t> b) {
        if (observed_labelling) {
          observed_labelling = false;
          return true;
        }
        std::fill(labels.begin(), labels.end(), 0);
        for (const std::size_t i : b) labels[i] = 1;
        const detail::Wanted want{tally[0].wanted(), tally[1].wanted(), tally[2].wanted()};
        const Statistics s = refit_statistics(factor, trend, labels, want);
        bool missing = false, more = false;
        for (std::size_t k = 0; k < 3; ++k) {
          if (!tally[k].wanted()) continue;
          const std::optional<double> v = statistic(s, k);
          missing = missing || !v;
          tally[k].add(!v || *v >= tally[k].threshold);
          more = more || tally[k].wanted();
        }
        if (missing) ++out.not_computable;
        return more;
      });
  out.labellings = l.total;
  out.exact = exact;
  out.exceedances = exact ? 0 : options.exceedances;
  auto p = [&](const Tally& t, std::optional<double>& pv, std::uint64_t& count, bool& stopped) {
    if (!std::isfinite(t.threshold)) return;
    pv = t.sampled ? t.sampled->p() : static_cast<double>(t.reached) / static_cast<double>(t.visited);
    count = t.sampled ? t.sampled->labellings() : t.visited;
    stopped = t.sampled && t.sampled->stopped_early();
  };
  p(tally[0], out.p_interaction, out.labellings_interaction, out.stopped_interaction);
  p(tally[1], out.p_condition, out.labellings_condition, out.stopped_condition);
  p(tally[2], out.p_slope_difference, out.labellings_slope, out.stopped_slope);
}

}  // namespace

RelabelledConditionTests relabel_condition_tests(const LongData& data,
                                                 const std::vector<std::string>& group_levels,
                                                 const RelabellingOptions& options) {
  check_arguments(data, group_levels, options);
  if (options.within || group_levels.size() > 2) return detail::relabel_general(data, group_levels, options);
  const Membership m = assign_participants(data, group_levels);
  const detail::RefitData d = detail::summarise(data, m.row_person, m.in_b.size());
  FactorModel factor(d);
  TrendModel trend(d);
  RelabelledConditionTests out;
  const Statistics observed = refit_statistics(factor, trend, m.in_b, detail::Wanted{});
  out.interaction_f = observed.interaction_f;
  out.condition_f = observed.condition_f;
  out.slope_difference_t = observed.slope_t;
  relabelling_p_values(factor, trend, m, options, observed, out);
  out.slope_differences_t = {out.slope_difference_t};
  out.p_slope_differences = {out.p_slope_difference};
  out.labellings_slopes = {out.labellings_slope};
  out.stopped_slopes = {out.stopped_slope};
  return out;
}

}  // namespace feint::models
