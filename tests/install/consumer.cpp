// Uses the installed library as another project would: metrics of metrics.md's worked example B,
// a one-sample t-test (R: t.test(c(.55,.61,.48,.7,.52), mu = .5)), and the whole study pipeline
// (load_study -> analyze -> StudyResults) on the study folder named by argv[1] (data/demo);
// exits non-zero when a number is off.
#include <cmath>
#include <cstdio>
#include <vector>

#include "feint/analysis/analyze.hpp"
#include "feint/metrics/trial_metrics.hpp"
#include "feint/stats/ttest.hpp"

int main(int argc, char** argv) {
  feint::io::Trial trial;
  trial.target = 1.0;
  trial.pad_speed = 0.25;
  for (int i = 0; i <= 10; ++i) trial.times.push_back(i);
  trial.pads = {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1};
  feint::metrics::MetricSettings speed;  // worked example B's `speed` value (raw is the default)
  speed.norm = feint::metrics::ConfusionNorm::speed;
  const auto score = feint::metrics::score_trial(trial, speed);
  const std::vector<double> x{0.55, 0.61, 0.48, 0.7, 0.52};
  const auto t = feint::stats::t_test_one_sample(x, 0.5);
  std::printf("error %.15g confusion %.15g t %.15g\n", score.error, score.confusion, *t.statistic);
  const bool ok = std::fabs(score.error - 115.0 / 144) < 1e-12 &&
                  std::fabs(score.confusion - 217.0 / 360) < 1e-12 &&
                  std::fabs(*t.statistic - 1.8753561398542429) < 1e-12;
  if (!ok || argc < 2) return 1;

  feint::analysis::AnalysisSettings settings;
  settings.compare = "adaptive,random";
  const feint::analysis::Study study = feint::analysis::load_study(argv[1], settings);
  const feint::analysis::StudyResults results = feint::analysis::analyze(study, "consumer");
  // The demo: 60 participants x 20 iterations; the Table 1 mean error of the first row is the
  // mean of the adaptive participants' error at iteration 1, as the scores give it.
  const auto& row = results.table1.rows.front();
  double sum = 0;
  int n = 0;
  for (const auto& r : results.scores.records) {
    if (r.condition == row.group1 && r.iteration == *row.iteration && r.values[0]) {
      sum += *r.values[0];
      ++n;
    }
  }
  std::printf("study %s: %llu trials, Table 1 row 1 mean %.15g (n = %d)\n", results.study.c_str(),
              static_cast<unsigned long long>(results.diagnostics.scoring.trials_scored),
              *row.result.mean1, n);
  return results.diagnostics.scoring.trials_scored == 1200 && n == 30 &&
                 std::fabs(*row.result.mean1 - sum / n) < 1e-12 && results.model.has_value()
             ? 0
             : 1;
}
