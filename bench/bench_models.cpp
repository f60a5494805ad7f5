// Benchmarks of the repeated-measures models: the mixed ANOVA and the linear mixed model
// (REML fit, Satterthwaite df, type-III table) of the paper's design (2 conditions x 20 iterations,
// 30 participants each) and simulation power (studies per second).
//   cmake -S . -B build -DFEINT_BUILD_BENCH=ON && cmake --build build --target bench_models
//   build/bench/bench_models
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "feint/models/mixed_anova.hpp"
#include "feint/models/mixed_model.hpp"
#include "feint/models/model_relabelling.hpp"
#include "feint/models/power_sim.hpp"

namespace {

using namespace feint::models;

SimulationDesign paper_design() {
  SimulationDesign d;
  for (int j = 0; j < 20; ++j) {
    d.means_a.push_back(0.6);
    d.means_b.push_back(0.6 - 0.004 * j);
  }
  d.sd_participant = 0.1;
  d.sd_residual = 0.15;
  return d;
}

std::vector<Observation> paper_observations() {
  const auto study = detail::analyse_simulated_study(paper_design(), {}, 0);
  std::vector<Observation> obs;
  for (std::size_t i = 0; i < 60; ++i) {
    for (std::size_t j = 0; j < 20; ++j) {
      obs.push_back({"P" + std::to_string(i), i < 30 ? "adaptive" : "random",
                     static_cast<long long>(j + 1), study.y[i * 20 + j], 0});
    }
  }
  return obs;
}

LongData paper_long_data() {
  LongData d;
  for (const auto& o : paper_observations()) {
    d.participant.push_back(o.participant);
    d.group.push_back(o.condition);
    d.time.push_back(static_cast<double>(o.iteration));
    d.y.push_back(*o.value);
  }
  return d;
}

void BM_MixedAnovaPaperDesign(benchmark::State& state) {
  const auto obs = paper_observations();
  for (auto _ : state) {
    const WideDesign d = make_wide_design(obs, "error", "bench");
    benchmark::DoNotOptimize(mixed_anova(d));
  }
}
BENCHMARK(BM_MixedAnovaPaperDesign)->Unit(benchmark::kMicrosecond);

// fit_mixed_model alone (no CSV, no rendering): iteration as a factor (random intercept), or a
// linear trend with a random slope (the slowest: Nelder-Mead over three parameters).
void BM_MixedModelPaperDesign(benchmark::State& state) {
  const LongData d = paper_long_data();
  ModelSpec spec;
  if (state.range(0) == 1) {
    spec.time_scale = TimeScale::linear;
    spec.random_slope = true;
  }
  for (auto _ : state) benchmark::DoNotOptimize(fit_mixed_model(d, spec, true));
}
BENCHMARK(BM_MixedModelPaperDesign)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The findings' relabelling p-values of the model tests: both random-intercept models refitted
// under each of `range(0)` relabellings of the paper's design (plus the observed labelling);
// items per second = refits of both models.
void BM_ModelRelabellingPaperDesign(benchmark::State& state) {
  const LongData d = paper_long_data();
  RelabellingOptions options;
  options.permutations = static_cast<std::uint64_t>(state.range(0));
  options.exceedances = 0;  // every labelling drawn: the cost per labelling, not the sequential stop
  for (auto _ : state) benchmark::DoNotOptimize(relabel_condition_tests(d, {"adaptive", "random"}, options));
  state.SetItemsProcessed(state.iterations() * (state.range(0) + 1));
}
BENCHMARK(BM_ModelRelabellingPaperDesign)->Arg(999)->Arg(9999)->Unit(benchmark::kMillisecond);

void BM_SimulationPower(benchmark::State& state) {
  SimulationOptions o;
  o.studies = static_cast<std::size_t>(state.range(0));
  o.threads = static_cast<unsigned>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(simulate_power(paper_design(), o));
  state.counters["studies_per_s"] =
      benchmark::Counter(static_cast<double>(o.studies) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulationPower)
    ->Args({10000, 1})
    ->Args({10000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
