// Power of an adaptive-vs-random study from simulated goal-inference participants
// (feint/sim/study_power.hpp).
#include "feint/sim/study_power.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::sim {

StudyTest simulate_study_test(const StudySettings& study, int from_iteration) {
  std::vector<double> adaptive, random;
  for (int i = 0; i < 2 * study.participants; ++i) {
    const ParticipantRecord p = simulate_participant(study, i);
    double sum = 0;
    int n = 0;
    for (const auto& tr : p.trials) {
      if (tr.iteration < from_iteration) continue;
      sum += tr.error;
      ++n;
    }
    (p.condition == Algorithm::adaptive ? adaptive : random).push_back(sum / n);
  }
  stats::TestOptions options;
  options.alternative = stats::Alternative::greater;
  const auto r = stats::t_test_welch(adaptive, random, options);
  StudyTest out;
  out.p_value = r.p_value.value_or(1.0);  // a study whose test cannot be computed does not reject
  double ma = 0, mr = 0;
  for (double x : adaptive) ma += x;
  for (double x : random) mr += x;
  out.difference = ma / static_cast<double>(adaptive.size()) - mr / static_cast<double>(random.size());
  return out;
}

StudyPowerResult study_power(const StudyPowerSettings& settings) {
  if (settings.participants.empty()) throw UsageError("study power: no numbers of participants given");
  for (int n : settings.participants) {
    if (n < 2) throw UsageError(fmt::format("study power: {} participants per condition: need at least 2", n));
  }
  if (settings.studies == 0) throw UsageError("study power: the number of simulated studies must be >= 1");
  if (!(settings.alpha > 0 && settings.alpha < 1)) {
    throw UsageError(fmt::format("study power: alpha {} is outside (0, 1)", settings.alpha));
  }
  if (settings.from_iteration < 1 || settings.from_iteration > settings.study.iterations) {
    throw UsageError(fmt::format("study power: --from-iteration {} is outside 1..{}", settings.from_iteration,
                                 settings.study.iterations));
  }
  validate(settings.study.geometry);
  validate(settings.study.observer);

  StudyPowerResult result;
  result.settings = settings;
  const unsigned threads = std::max(1u, settings.threads);
  for (int n : settings.participants) {
    std::vector<StudyTest> tests(settings.studies);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      for (std::size_t s; (s = next.fetch_add(1)) < settings.studies;) {
        StudySettings study = settings.study;
        study.participants = n;
        std::uint64_t mix = settings.seed ^ (static_cast<std::uint64_t>(n) << 32) ^ s;
        study.seed = splitmix64(mix);
        tests[s] = simulate_study_test(study, settings.from_iteration);
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    std::size_t rejected = 0;
    double diff = 0;
    for (const auto& t : tests) {
      rejected += t.p_value < settings.alpha;
      diff += t.difference;
    }
    StudyPowerPoint pt;
    pt.participants = n;
    const double k = static_cast<double>(settings.studies);
    pt.power = static_cast<double>(rejected) / k;
    pt.mc_se = std::sqrt(pt.power * (1 - pt.power) / k);
    pt.mean_difference = diff / k;
    result.points.push_back(pt);
    if (!result.smallest_n_for_target && pt.power >= settings.target_power) result.smallest_n_for_target = n;
  }
  return result;
}

}  // namespace feint::sim
