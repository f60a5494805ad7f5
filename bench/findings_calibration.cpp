// findings_calibration: the findings of `feint analyze` checked against a known truth over studies
// made by `feint simulate study`'s simulator (docs/findings.md "Calibration
// against truth"). Own main (a driver, not a Google Benchmark):
//
//   findings_calibration [NULL_STUDIES=200] [PLANTED_STUDIES=100] [PARTICIPANTS=30]
//                        [PLANTED_PARTICIPANTS=60] [THREADS=2] [BF_STUDIES=10] [DESIGN=between]
//                        [CONDITIONS=adaptive,random]
//
// DESIGN within: every participant in both conditions (counterbalanced blocks; PARTICIPANTS in
// all), analysed as a within study (paired tests, sign-flip maxT; docs/analysis.md "Designs").
// CONDITIONS as `feint simulate study --conditions`: a=random,b=random,c=random is a null study of
// three conditions (one algorithm under three names), analysed with no pair named: the models'
// omnibus tests and the protected pairs.
//
// 1. Null: the adaptive condition with lambda = 0 (its selection is then uniform, as random's, so
//    the condition labels carry no effect), PARTICIPANTS per condition, 20 iterations, seeds
//    1000.. : for every headline finding the rate of a false "evidence for a difference" with its
//    Clopper-Pearson 95 % interval, and the rate of "evidence for no difference".
// 2. Planted: the simulator's adaptive (lambda 0.5) against random, PLANTED_PARTICIPANTS per
//    condition, seeds 5000.. : the rate of "evidence for a difference" per headline finding.
// 3. BF01 under the null at n = 10, 40, 160 per condition (BF_STUDIES studies each, seeds 9000..):
//    the median BF01 of the two-sample t tests (per-iteration contrasts and questionnaire items).
// Every study is seeded; the tables are the same for any THREADS.
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <cstdlib>
#include <string>
#include <vector>

#include "feint/analysis/calibration.hpp"

namespace {

using feint::analysis::CalibrationOutcome;
using feint::analysis::Strength;

double cpu_seconds() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// Under the null, z = estimate / SE of an exposure-slope difference is standard normal when the SE
// is right: its SD over studies is the factor by which the reported SE is too small (> 1) or large.
void print_se_check(const std::vector<CalibrationOutcome>& outcomes) {
  std::map<std::string, std::vector<double>> est, z;
  for (const auto& o : outcomes)
    for (std::size_t i = 0; i < o.contrast_names.size(); ++i) {
      est[o.contrast_names[i]].push_back(o.contrast_estimates[i]);
      z[o.contrast_names[i]].push_back(o.contrast_estimates[i] / o.contrast_se[i]);
    }
  fmt::print("| exposure-slope difference | studies | mean estimate | SD of estimates | mean SE | SD of z | "
             "share |z| > 1.96 |\n|---|---|---|---|---|---|---|\n");
  for (const auto& [name, e] : est) {
    const auto& zs = z[name];
    auto mean = [](const std::vector<double>& v) {
      double s = 0;
      for (double x : v) s += x;
      return s / static_cast<double>(v.size());
    };
    auto sd = [&](const std::vector<double>& v) {
      const double m = mean(v);
      double s = 0;
      for (double x : v) s += (x - m) * (x - m);
      return std::sqrt(s / static_cast<double>(v.size() - 1));
    };
    double se = 0;
    int big = 0;
    for (std::size_t i = 0; i < e.size(); ++i) {
      se += e[i] / zs[i];
      big += std::abs(zs[i]) > 1.96;
    }
    fmt::print("| {} | {} | {:.4f} | {:.4f} | {:.4f} | {:.2f} | {:.1f} % |\n", name, e.size(), mean(e), sd(e),
               se / static_cast<double>(e.size()), sd(zs), 100.0 * big / static_cast<double>(e.size()));
  }
  fmt::print("\n");
}

void print_rates(const std::vector<CalibrationOutcome>& outcomes, Strength strength, const std::string& what) {
  fmt::print("| headline finding | studies | {} | rate | 95% CI |\n|---|---|---|---|---|\n", what);
  for (const auto& r : feint::analysis::calibration_rates(outcomes, strength)) {
    fmt::print("| {} | {} | {} | {:.1f} % | [{:.1f}, {:.1f}] % |\n", r.family, r.studies, r.count, 100 * r.rate,
               100 * r.low, 100 * r.high);
  }
  fmt::print("\n");
}

std::vector<CalibrationOutcome> run(const char* label, feint::sim::StudyOptions o, std::uint64_t seed, int n,
                                    unsigned threads) {
  const auto w0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  // Three or more conditions: no pair is named; the models' omnibus tests and their pairs compare them.
  auto settings = feint::analysis::calibration_analysis_settings();
  if (std::count(o.conditions.begin(), o.conditions.end(), ',') >= 2) settings.compare.clear();
  auto out = feint::analysis::calibration_run(o, seed, n, threads, settings);
  fmt::print("{}: {} studies of {} participants x {} iterations (lambda {}), seeds {}..{}: "
             "{:.0f} s wall, {:.0f} s CPU\n\n",
             label, n,
             o.design == "within" ? fmt::format("{} (each in every condition: {})", o.participants, o.conditions)
                                  : fmt::format("{} per condition ({})", o.participants, o.conditions),
             o.iterations, o.lambda, seed,
             seed + static_cast<std::uint64_t>(n) - 1,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(), cpu_seconds() - c0);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  auto arg = [&](int i, int def) { return argc > i ? std::atoi(argv[i]) : def; };
  const int null_studies = arg(1, 200), planted_studies = arg(2, 100);
  const int participants = arg(3, 30), planted_participants = arg(4, 60);
  const auto threads = static_cast<unsigned>(arg(5, 2));
  const int bf_studies = arg(6, 10);

  feint::sim::StudyOptions o;  // as `feint simulate study`: goal-inference participants, 25 Hz
  o.iterations = 20;
  if (argc > 7) o.design = argv[7];
  if (argc > 8) o.conditions = argv[8];  // e.g. a=random,b=random,c=random: a null study of three
  if (null_studies > 0) {
    o.participants = participants;
    o.lambda = 0;
    const auto null = run("Null (adaptive with lambda 0 = random)", o, 1000, null_studies, threads);
    print_rates(null, Strength::evidence_for_difference, "false \"evidence for a difference\"");
    print_rates(null, Strength::evidence_for_no_difference, "\"evidence for no difference\"");
    print_se_check(null);
  }
  if (planted_studies > 0) {
    o.participants = planted_participants;
    o.lambda = 0.5;
    const auto planted = run("Planted (adaptive lambda 0.5 vs random)", o, 5000, planted_studies, threads);
    print_rates(planted, Strength::evidence_for_difference, "\"evidence for a difference\"");
  }
  if (bf_studies > 0) {
    fmt::print("| n per condition | studies | two-sample tests | median BF01 |\n|---|---|---|---|\n");
    for (const int n : {10, 40, 160}) {
      o.participants = n;
      o.lambda = 0;
      const auto outs = feint::analysis::calibration_run(o, 9000, bf_studies, threads);
      std::vector<double> bf;
      for (const auto& x : outs) bf.insert(bf.end(), x.bf01.begin(), x.bf01.end());
      std::sort(bf.begin(), bf.end());
      const double median = bf.empty() ? 0 : bf.size() % 2 ? bf[bf.size() / 2]
                                                            : (bf[bf.size() / 2 - 1] + bf[bf.size() / 2]) / 2;
      fmt::print("| {} | {} | {} | {:.2f} |\n", n, bf_studies, bf.size(), median);
    }
  }
  return 0;
}
