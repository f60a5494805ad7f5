// Uses the installed library as another project would: metrics of metrics.md's worked example B
// and a one-sample t-test (R: t.test(c(.55,.61,.48,.7,.52), mu = .5)); exits non-zero when off.
#include <cmath>
#include <cstdio>
#include <vector>

#include "feint/metrics/trial_metrics.hpp"
#include "feint/stats/ttest.hpp"

int main() {
  feint::io::Trial trial;
  trial.target = 1.0;
  trial.pad_speed = 0.25;
  for (int i = 0; i <= 10; ++i) trial.times.push_back(i);
  trial.pads = {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1};
  const auto score = feint::metrics::score_trial(trial, feint::metrics::MetricSettings{});
  const std::vector<double> x{0.55, 0.61, 0.48, 0.7, 0.52};
  const auto t = feint::stats::t_test_one_sample(x, 0.5);
  std::printf("error %.15g confusion %.15g t %.15g\n", score.error, score.confusion, *t.statistic);
  const bool ok = std::fabs(score.error - 115.0 / 144) < 1e-12 &&
                  std::fabs(score.confusion - 217.0 / 360) < 1e-12 &&
                  std::fabs(*t.statistic - 1.8753561398542429) < 1e-12;
  return ok ? 0 : 1;
}
