// Power of an adaptive-vs-random study from simulated goal-inference participants
// (feint/sim/study_power.hpp).
#include "feint/sim/study_power.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <span>
#include <thread>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/rng.hpp"
#include "feint/stats/ttest.hpp"

namespace feint::sim {

namespace {

/// The robot's path for every strategy, version and target, computed once for a run of studies:
/// simulate_participant computes one per trial, and that was about 40 % of the time.
class PathBook {
 public:
  explicit PathBook(const Geometry& g) {
    for (Strategy s : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous, Strategy::optimal}) {
      for (Variant v : {Variant::main, Variant::v2}) {
        if (s == Strategy::optimal && v == Variant::v2) continue;  // the optimal path has no version 2
        for (Target t : {Target::left, Target::right}) paths_[index(s, v, t)] = trajectory(s, v, t, g);
      }
    }
  }
  const std::vector<TrajectorySample>& operator()(const Iteration& it) const {
    return paths_[index(it.strategy, it.variant, it.target)];
  }

 private:
  static std::size_t index(Strategy s, Variant v, Target t) {
    return (static_cast<std::size_t>(s) * 2 + static_cast<std::size_t>(v)) * 2 + static_cast<std::size_t>(t);
  }
  std::array<std::vector<TrajectorySample>, 16> paths_;
};

/// A participant's mean trial error over iterations from_iteration..N: the trials of
/// simulate_participant (random stream `stream` of the study's seed, drawn in the same order), its
/// paths from `paths`.
double later_mean_error(const StudySettings& study, std::uint64_t stream, Algorithm condition, int from_iteration,
                        const PathBook& paths) {
  Rng rng = Rng::stream(study.seed, stream);
  RunSettings run;
  run.algorithm = condition;
  run.lambda = study.lambda;
  run.iterations = study.iterations;
  const std::vector<Iteration> its = generate_run(run, rng);
  Observer observer(study.observer);
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < its.size(); ++i) {
    const Iteration& it = its[i];
    const auto pad = observer.watch(paths(it), it.strategy, it.variant, it.target, study.geometry, rng);
    observer.remember(it.strategy, it.variant);
    if (static_cast<int>(i) + 1 < from_iteration) continue;  // its error is not used
    sum += trial_error(pad, it.target == Target::left ? 0.0 : 1.0);
    ++n;
  }
  return sum / n;
}

/// The paper's H1 on each participant's later mean error: Welch's t, one-sided, adaptive greater.
StudyTest welch_test(std::span<const double> adaptive, std::span<const double> random) {
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

/// One simulated study at the largest size: the later mean errors of participants 0..size-1 of
/// each condition, participant k of condition c on stream 2k + c, so that a study of size n is the
/// first n of each condition (the same people at every size).
struct StudyDraw {
  std::vector<double> adaptive, random;
};

StudyDraw simulate_draw(const StudySettings& study, int size, int from_iteration, const PathBook& paths) {
  StudyDraw d;
  for (int k = 0; k < size; ++k) {
    const auto stream = 2 * static_cast<std::uint64_t>(k);
    d.adaptive.push_back(later_mean_error(study, stream, Algorithm::adaptive, from_iteration, paths));
    d.random.push_back(later_mean_error(study, stream + 1, Algorithm::random, from_iteration, paths));
  }
  return d;
}

}  // namespace

StudyTest simulate_study_test(const StudySettings& study, int from_iteration) {
  validate(study.geometry);
  if (study.participants < 1) throw UsageError("participants per condition must be >= 1");
  const PathBook paths(study.geometry);
  std::vector<double> adaptive, random;
  for (int i = 0; i < 2 * study.participants; ++i) {
    const Algorithm condition = kStudyConditions[static_cast<std::size_t>(i / study.participants)];
    const double e = later_mean_error(study, static_cast<std::uint64_t>(i), condition, from_iteration, paths);
    (i < study.participants ? adaptive : random).push_back(e);
  }
  return welch_test(adaptive, random);
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
  const PathBook paths(settings.study.geometry);
  const int largest = *std::max_element(settings.participants.begin(), settings.participants.end());
  const std::size_t sizes = settings.participants.size();
  // tests[i * studies + s]: study s at size participants[i].
  std::vector<StudyTest> tests(sizes * settings.studies);
  std::atomic<std::size_t> next{0}, done{0};
  const std::uint64_t per_study = 2 * static_cast<std::uint64_t>(largest);
  // Each study depends on its seed alone, whichever thread runs it. The seed is scrambled before
  // the study's number is mixed in: seed ^ s alone would give seeds 1 and 2 the same set of studies.
  std::uint64_t state = settings.seed;
  const std::uint64_t key = splitmix64(state);
  auto work = [&](bool report) {
    for (std::size_t s; (s = next.fetch_add(1)) < settings.studies;) {
      StudySettings study = settings.study;
      std::uint64_t mix = key ^ s;
      study.seed = splitmix64(mix);
      const StudyDraw d = simulate_draw(study, largest, settings.from_iteration, paths);
      for (std::size_t i = 0; i < sizes; ++i) {
        const auto n = static_cast<std::size_t>(settings.participants[i]);
        tests[i * settings.studies + s] =
            welch_test(std::span(d.adaptive).first(n), std::span(d.random).first(n));
      }
      const std::size_t finished = done.fetch_add(1) + 1;
      // Only the calling thread reports, so the callback needs no lock.
      if (report && settings.on_progress) settings.on_progress(per_study * finished, per_study * settings.studies);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, false);
  work(true);
  for (auto& t : pool) t.join();
  for (std::size_t i = 0; i < sizes; ++i) {
    const int n = settings.participants[i];
    const std::span<const StudyTest> at_n(tests.data() + i * settings.studies, settings.studies);
    std::size_t rejected = 0;
    double diff = 0;
    for (const auto& t : at_n) {
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
