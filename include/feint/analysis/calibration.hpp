// feint/analysis/calibration.hpp - the findings checked against a known truth:
// studies made by the simulator of `feint simulate study` (sim::write_study), analysed as
// `feint analyze` analyses them (load_study -> analyze -> study_findings), and the headline claim
// of each hypothesis counted. docs/findings.md "Calibration against truth" has the rates.
//
// A true null: the adaptive condition with lambda = 0 never moves probability away from a shown
// strategy, so its strategies, versions and targets are uniform and independent, as the random
// condition's: the condition labels carry no effect on anything (logs and questionnaire alike).
// A planted effect: lambda > 0 (the simulator's adaptive algorithm against random), whose effect
// is the goal-inference participant's slower learning under adaptive selection.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "feint/analysis/findings.hpp"
#include "feint/analysis/settings.hpp"
#include "feint/sim/options.hpp"

namespace feint::analysis {

/// The headline claims of one analysed study, one per family, in a fixed order (calibration_
/// families): for each metric, the Holm-corrected per-iteration contrasts; the mixed-model family
/// (Holm over its 3 tests: "evidence for a difference" when any of them earns it) and each of its
/// members; the exposure family (Holm over the strategies; any strategy); for the questionnaire,
/// each item between the conditions and "any item" (no correction over the items: each item is its
/// own finding).
struct CalibrationOutcome {
  std::uint64_t seed = 0;
  std::vector<std::string> families;  ///< labels, e.g. "H1 per-iteration contrasts: error"
  std::vector<Strength> strengths;    ///< the headline strength of each family
  /// BF01 of every two-sample t test the findings rest on (per-iteration contrasts, questionnaire
  /// items between the conditions): under the null these grow with n.
  std::vector<double> bf01;
  /// Every exposure-slope difference between the conditions (report's exposure table), named
  /// "METRIC STRATEGY": its estimate and reported SE, to compare the SE with the spread of the
  /// estimates over studies (under the null the mean of estimate / SE is 0 and its SD 1).
  std::vector<std::string> contrast_names;
  std::vector<double> contrast_estimates, contrast_se;
};

/// The settings `feint analyze` runs the demo with (data/demo/feint.toml): compare adaptive,random;
/// error = 0.5 and confusion = 0.95 (raw confusion, the paper's scale); Likert reference 3.5.
AnalysisSettings calibration_analysis_settings();

/// Simulates the study of `study` (seed included) into a private temporary folder, analyses it as
/// `feint analyze` does, and returns its headline claims; the folder is removed however it ends.
CalibrationOutcome calibration_study(const sim::StudyOptions& study,
                                     const AnalysisSettings& settings = calibration_analysis_settings());

/// Runs `studies` studies with seeds first_seed, first_seed + 1, ... on `threads` threads (0 = all
/// cores); outcome i depends on its seed only, so the result is the same for any thread count.
std::vector<CalibrationOutcome> calibration_run(sim::StudyOptions study, std::uint64_t first_seed,
                                                int studies, unsigned threads = 0,
                                                const AnalysisSettings& settings = calibration_analysis_settings());

/// The rate of one strength of one family over a run, with its exact (Clopper-Pearson) 95 % interval.
struct CalibrationRate {
  std::string family;
  int count = 0, studies = 0;
  double rate = 0, low = 0, high = 0;
};
/// For each family of the outcomes (in their order), the rate of `strength`.
std::vector<CalibrationRate> calibration_rates(const std::vector<CalibrationOutcome>& outcomes,
                                               Strength strength);

/// Clopper-Pearson interval of k successes in n trials at level `conf`.
std::pair<double, double> clopper_pearson(int k, int n, double conf = 0.95);

}  // namespace feint::analysis
