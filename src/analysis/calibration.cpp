// The findings against a known truth: see feint/analysis/calibration.hpp.
#include "feint/analysis/calibration.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <thread>

#include <boost/math/distributions/beta.hpp>
#include <fmt/format.h>

#include "feint/analysis/analyze.hpp"
#include "feint/analysis/study.hpp"
#include "feint/error.hpp"
#include "feint/sim/study.hpp"
#include "scratch_folder.hpp"

namespace feint::analysis {

namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

const Finding* find(const std::vector<Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

/// The headline of a family whose members are corrected already, by family_finding's rule: a
/// difference when any member earns it; no difference only when every computed member does; not
/// computable when none was computed; otherwise no evidence either way.
Strength any_of(const std::vector<const Finding*>& members) {
  int computed = 0, no_difference = 0;
  for (const Finding* f : members) {
    if (f->strength == Strength::evidence_for_difference) return Strength::evidence_for_difference;
    computed += f->strength != Strength::not_computable;
    no_difference += f->strength == Strength::evidence_for_no_difference;
  }
  if (computed == 0) return Strength::not_computable;
  return no_difference == computed ? Strength::evidence_for_no_difference : Strength::no_evidence_either_way;
}

}  // namespace

AnalysisSettings calibration_analysis_settings() {
  AnalysisSettings s;
  s.compare = "adaptive,random";
  s.likert.reference = 3.5;
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.95"};
  return s;
}

CalibrationOutcome calibration_study(const sim::StudyOptions& options, const AnalysisSettings& settings) {
  const detail::ScratchFolder tmp("feint-calibration");
  const sim::StudySettings study = sim::study_settings(options);
  sim::write_study(study, tmp.path().string());
  const StudyResults r = analyze(load_study(tmp.path().string(), settings), "calibration");

  CalibrationOutcome out;
  out.seed = options.seed;
  auto add = [&](std::string family, Strength s) {
    out.families.push_back(std::move(family));
    out.strengths.push_back(s);
  };
  const auto metrics = parse_metric_specs(settings.metrics);
  const bool pairs = study.conditions.size() > 2;
  // Three or more conditions and no pair named: the iteration family is the omnibus F per
  // iteration, maxF-adjusted (docs/findings.md); a named pair keeps its maxT contrasts.
  const bool omnibus = pairs && settings.compare.empty();
  for (const auto& m : metrics) {
    const Finding* f = find(r.findings, "H1-iterations-" + m.column);
    const char* label = omnibus ? "H1 per-iteration omnibus F (maxF over iterations): "
                                : "H1 per-iteration contrasts (maxT over iterations): ";
    add(label + m.column, f ? f->strength : Strength::not_computable);
  }
  for (const auto& m : metrics) {
    // The model's tests: interaction, condition, and one slope difference per condition but the
    // first (H1-model-trend-METRIC with two conditions, H1-model-trend-METRIC-LEVEL with more).
    std::vector<const Finding*> members, slopes, pair_members;
    for (const auto& f : r.findings) {
      if (f.id == "H1-model-trend-" + m.column || starts_with(f.id, "H1-model-trend-" + m.column + "-"))
        slopes.push_back(&f);
      if (starts_with(f.id, "H1-model-pair-" + m.column + "-")) pair_members.push_back(&f);
    }
    for (const char* part : {"interaction", "condition"})
      if (const Finding* f = find(r.findings, fmt::format("H1-model-{}-{}", part, m.column))) members.push_back(f);
    members.insert(members.end(), slopes.begin(), slopes.end());
    add(fmt::format("H1 mixed models (Holm over {} tests): {}", pairs ? "its" : "3", m.column), any_of(members));
    for (const char* part : {"interaction", "condition"}) {
      const Finding* f = find(r.findings, fmt::format("H1-model-{}-{}", part, m.column));
      add(fmt::format("  {} ({})", part, m.column), f ? f->strength : Strength::not_computable);
    }
    add(fmt::format("  slope difference{} ({})", pairs ? "s, any" : "", m.column), any_of(slopes));
    if (pairs) add(fmt::format("H1 pairs of conditions (Tukey, protected), any: {}", m.column), any_of(pair_members));
  }
  for (const auto& m : metrics) {
    std::vector<const Finding*> members;
    for (const auto& f : r.findings)
      if (starts_with(f.id, "H1-exposure-" + m.column + "-") || f.id == "H1-exposure-" + m.column)
        members.push_back(&f);
    add("H1 exposure slopes by condition (Holm over strategies): " + m.column, any_of(members));
  }
  if (r.likert_compare) {
    std::vector<const Finding*> members;
    for (const auto& f : r.findings)
      if (starts_with(f.id, "H2-compare-")) members.push_back(&f);
    for (const Finding* f : members) add("H2 questionnaire between conditions: " + f->id.substr(11), f->strength);
    add("H2 questionnaire: any item (no correction over items)", any_of(members));
    for (const auto& row : r.likert_compare->rows)
      if (row.result.bf01 && (row.result.test == "welch_t" || row.result.test == "student_t"))
        out.bf01.push_back(*row.result.bf01);
  }
  for (const auto& t : r.exposure)
    for (const auto& d : t.result.differences)
      if (d.test.computed && d.test.estimate) {
        out.contrast_names.push_back(t.metric + " " + d.strategy);
        out.contrast_estimates.push_back(*d.test.estimate);
        out.contrast_se.push_back(d.std_error);
      }
  if (r.comparison)
    for (const auto& row : r.comparison->rows)
      if (row.result.bf01 && (row.result.test == "welch_t" || row.result.test == "student_t"))
        out.bf01.push_back(*row.result.bf01);
  return out;
}

std::vector<CalibrationOutcome> calibration_run(sim::StudyOptions study, std::uint64_t first_seed, int studies,
                                                unsigned threads, const AnalysisSettings& settings) {
  if (studies < 0) throw UsageError("the number of studies must be >= 0");
  std::vector<CalibrationOutcome> out(static_cast<std::size_t>(studies));
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(std::max(studies, 1)));
  std::atomic<int> next{0};
  std::vector<std::string> errors(threads);
  auto work = [&](unsigned t) {
    try {
      for (int i = next++; i < studies; i = next++) {
        sim::StudyOptions o = study;
        o.seed = first_seed + static_cast<std::uint64_t>(i);
        out[static_cast<std::size_t>(i)] = calibration_study(o, settings);
      }
    } catch (const std::exception& e) {
      errors[t] = e.what();
      next = studies;  // stop the others early
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& e : errors)
    if (!e.empty()) throw InvalidData("calibration study failed: " + e);
  return out;
}

std::pair<double, double> clopper_pearson(int k, int n, double conf) {
  if (n <= 0 || k < 0 || k > n) throw UsageError("clopper_pearson needs 0 <= k <= n, n > 0");
  const double a = (1 - conf) / 2;
  const double low = k == 0 ? 0.0 : boost::math::quantile(boost::math::beta_distribution<>(k, n - k + 1), a);
  const double high = k == n ? 1.0 : boost::math::quantile(boost::math::beta_distribution<>(k + 1, n - k), 1 - a);
  return {low, high};
}

std::vector<CalibrationRate> calibration_rates(const std::vector<CalibrationOutcome>& outcomes, Strength strength) {
  std::vector<CalibrationRate> out;
  std::map<std::string, std::size_t> index;
  for (const auto& o : outcomes)
    for (std::size_t i = 0; i < o.families.size(); ++i) {
      auto [it, added] = index.emplace(o.families[i], out.size());
      if (added) out.push_back({o.families[i], 0, 0, 0, 0, 0});
      CalibrationRate& r = out[it->second];
      ++r.studies;
      r.count += o.strengths[i] == strength ? 1 : 0;
    }
  for (auto& r : out) {
    r.rate = static_cast<double>(r.count) / r.studies;
    std::tie(r.low, r.high) = clopper_pearson(r.count, r.studies);
  }
  return out;
}

}  // namespace feint::analysis
