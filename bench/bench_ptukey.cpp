// Benchmarks of the Tukey p-value: 1 - ptukey against ptukey_upper (the upper tail as its own
// integral, docs/mixed-model.md), for one family of 20 means (190 contrasts) at the demo's anova
// df (58) and at infinite df, q from 0.5 to 12 (p from 1 to ~1e-10). The per-k tables are built
// before the timing (once per k and thread: ~1 ms for ptukey's, more for ptukey_upper's).
//   cmake -S . -B build -DFEINT_BUILD_BENCH=ON && cmake --build build --target bench_ptukey
//   build/bench/bench_ptukey
#include <benchmark/benchmark.h>

#include <limits>

#include "feint/models/studentized_range.hpp"

namespace {

using feint::models::ptukey;
using feint::models::ptukey_upper;

double df_of(const benchmark::State& state) {
  return state.range(0) == 0 ? std::numeric_limits<double>::infinity()
                             : static_cast<double>(state.range(0));
}

void BM_OneMinusPtukey(benchmark::State& state) {
  const double df = df_of(state);
  benchmark::DoNotOptimize(ptukey(3, 20, df));
  for (auto _ : state)
    for (int i = 0; i < 190; ++i) benchmark::DoNotOptimize(1 - ptukey(0.5 + 0.06 * i, 20, df));
}
BENCHMARK(BM_OneMinusPtukey)->Arg(58)->Arg(0)->Unit(benchmark::kMicrosecond);

void BM_PtukeyUpper(benchmark::State& state) {
  const double df = df_of(state);
  benchmark::DoNotOptimize(ptukey_upper(3, 20, df));
  for (auto _ : state)
    for (int i = 0; i < 190; ++i) benchmark::DoNotOptimize(ptukey_upper(0.5 + 0.06 * i, 20, df));
}
BENCHMARK(BM_PtukeyUpper)->Arg(58)->Arg(0)->Unit(benchmark::kMicrosecond);

// The cost of the first call for a k: the per-k tables (a new k each iteration).
void BM_PtukeyUpperFirstCall(benchmark::State& state) {
  double k = 2;
  for (auto _ : state) benchmark::DoNotOptimize(ptukey_upper(4, k++, 58));
}
BENCHMARK(BM_PtukeyUpperFirstCall)->Iterations(20)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
