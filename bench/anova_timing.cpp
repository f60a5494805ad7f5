// Driver of bench/run_anova_bench.sh: reads a scores CSV once, then fits the mixed ANOVA of one
// metric REPS times in-process and prints the seconds per fit (wall clock), the counterpart of the
// R side's system.time(replicate(REPS, aov_ez(...))).
//   anova_timing SCORES.csv METRIC REPS
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "feint/io/scores.hpp"
#include "feint/tables/anova.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: anova_timing SCORES.csv METRIC REPS\n");
    return 64;
  }
  feint::io::ScoresOptions so;
  so.metrics = {argv[2]};
  const auto scores = feint::io::load_scores(argv[1], so);
  const int reps = std::atoi(argv[3]);
  double sink = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < reps; ++r) {
    // From the long table each time, as aov_ez does from its data frame.
    const auto report =
        feint::tables::build_anova_report(scores, feint::models::SphericityCorrection::GG);
    sink += report.analyses[0].effects.back().f;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%.9g\n", s / reps);
  return sink > 0 ? 0 : 1;
}
