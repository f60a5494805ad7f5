// Fitting the goal-inference observer (feint/models/observer_fit.hpp; docs/observer.md "Speed").
//   BM_FitStudy60x20        fit_study on 60 participants x 20 iterations (two conditions of 30):
//                           per-participant fits, pooled fits, agreement; with and without the
//                           learning test.
//   BM_FitParticipant       one participant's fit (20 trials) with profile CIs.
//   BM_Coverage             parameter recovery over many simulated participants: the share of 95%
//                           profile CIs that cover the true beta and tau (counters), for the AR(1)
//                           model and for independent errors on every / on thinned samples.
//   BM_PointerCoverage      the same for the K-goal observer fitted to pointer traces drawn from
//                           its model (K = 3, random layouts and the row; pointer_observer_fit.hpp).
//   BM_PointerParticipant   one pointer participant's fit (8 trials, K = 3) with profile CIs.
#include <benchmark/benchmark.h>

#include "../tests/models/observer_test_paths.hpp"
#include "../tests/sim/pointer_observer_sim.hpp"
#include "feint/models/observer_fit.hpp"
#include "feint/models/pointer_observer_fit.hpp"

using namespace feint::models;
namespace tp = feint::testpaths;

namespace {

std::vector<ObservedTrial> study(int participants, int iterations) {
  std::vector<ObservedTrial> all;
  for (int p = 0; p < participants; ++p) {
    feint::Rng rng = feint::Rng::stream(99, static_cast<std::uint64_t>(p));
    const GoalObserver truth{0.8 + 0.02 * p, 0.2 + 0.005 * p, 0.5};
    auto trs = tp::simulate_participant(truth, iterations, 0.9, 0.02, rng, "P" + std::to_string(p));
    for (auto& t : trs) {
      t.condition = p < participants / 2 ? "adaptive" : "random";
      // Scores need pads in [0, 1].
      for (auto& x : t.pads) x = std::clamp(x, 0.0, 1.0);
    }
    all.insert(all.end(), trs.begin(), trs.end());
  }
  return all;
}

void BM_FitStudy60x20(benchmark::State& state) {
  const auto trials = study(60, 20);
  ObserverFitSettings s;
  s.learning = state.range(0) != 0;
  std::size_t samples = 0;
  for (const auto& t : trials) samples += t.times.size();
  for (auto _ : state) {
    auto r = fit_study(trials, s);
    benchmark::DoNotOptimize(r);
  }
  state.counters["pad_samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_FitStudy60x20)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_FitParticipant(benchmark::State& state) {
  const auto trials = study(1, 20);
  std::size_t evals = 0;
  for (auto _ : state) {
    auto f = fit_observer(trials, ObserverFitSettings{}, "P0");
    evals = f.evaluations;
    benchmark::DoNotOptimize(f);
  }
  state.counters["likelihood_evaluations"] = static_cast<double>(evals);
}
BENCHMARK(BM_FitParticipant)->Unit(benchmark::kMillisecond);

void BM_Coverage(benchmark::State& state) {
  const int studies = static_cast<int>(state.range(0));
  const PadNoise noise = state.range(1) == 0 ? PadNoise::ar1 : PadNoise::independent;
  const GoalObserver truth{1.5, 0.4, 0.5};
  ObserverFitSettings s;
  s.noise = noise;
  if (state.range(1) == 2) s.thin = 0.5;  // independent errors on one sample per 0.5 s
  int cb = 0, ct = 0, both = 0;
  for (auto _ : state) {
    cb = ct = both = 0;
    for (int k = 0; k < studies; ++k) {
      feint::Rng rng = feint::Rng::stream(4242, static_cast<std::uint64_t>(k));
      const auto trs = tp::simulate_participant(truth, 10, 0.9, 0.02, rng);
      const auto f = fit_observer(trs, s, "P");
      const auto& b = f.parameter("beta");
      const auto& t = f.parameter("tau");
      const bool xb = b.conf_low <= truth.beta && truth.beta <= b.conf_high;
      const bool xt = t.conf_low <= truth.tau && truth.tau <= t.conf_high;
      cb += xb;
      ct += xt;
      both += xb && xt;
    }
  }
  state.counters["beta_coverage"] = static_cast<double>(cb) / studies;
  state.counters["tau_coverage"] = static_cast<double>(ct) / studies;
  state.counters["joint_coverage"] = static_cast<double>(both) / studies;
}
// range(1): 0 = AR(1) on every sample, 1 = independent on every sample, 2 = independent, thinned.
BENCHMARK(BM_Coverage)->Args({1000, 0})->Args({200, 1})->Args({200, 2})->Iterations(1)->Unit(benchmark::kSecond);

void BM_PointerCoverage(benchmark::State& state) {
  const int studies = static_cast<int>(state.range(0));
  feint::testpointer::Coverage c;
  for (auto _ : state) c = feint::testpointer::pointer_coverage(studies, 8, 4242);
  state.counters["beta_coverage"] = static_cast<double>(c.beta) / studies;
  state.counters["tau_coverage"] = static_cast<double>(c.tau) / studies;
  state.counters["joint_coverage"] = static_cast<double>(c.both) / studies;
}
BENCHMARK(BM_PointerCoverage)->Arg(1000)->Iterations(1)->Unit(benchmark::kSecond);

void BM_PointerParticipant(benchmark::State& state) {
  feint::Rng rng(99);
  const auto trials = feint::testpointer::simulate_pointer_participant({}, 8, 3, true, rng);
  std::size_t evals = 0;
  for (auto _ : state) {
    auto f = fit_pointer_observer(trials, ObserverFitSettings{}, "P0");
    evals = f.evaluations;
    benchmark::DoNotOptimize(f);
  }
  state.counters["likelihood_evaluations"] = static_cast<double>(evals);
}
BENCHMARK(BM_PointerParticipant)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
