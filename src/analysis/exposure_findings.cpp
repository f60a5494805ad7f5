// H1's condition x exposure findings and the exposure input they read (exposure_findings.hpp,
// feint/analysis/study_findings.hpp).
#include "exposure_findings.hpp"

#include <cmath>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "feint/analysis/study_findings.hpp"
#include "feint/models/exposure.hpp"

namespace feint::analysis {

namespace detail {

namespace {

// The exposure finding of a metric whose exposure slopes could not be fitted, with the reason.
Finding exposure_not_computable(const std::string& metric, const std::string& source, const char* reason) {
  Finding f;
  f.id = "H1-exposure-" + metric;
  f.hypothesis = "H1";
  f.question = fmt::format("Does a strategy's effect on {} wear off with exposure differently under "
                           "the two conditions?", metric);
  f.strength = Strength::not_computable;
  f.evidence = to_string(f.strength);
  f.sentence = fmt::format("Exposure slopes of {} by condition: not computable ({}).", metric, reason);
  f.source = source;
  return f;
}

// The condition x exposure figure of a metric; else first against later exposures (the
// strategies figure when there are no traces).
std::string exposure_source(const StudyResults& r, const std::string& metric) {
  std::string source = r.figures.traces.empty() ? "fig-strategies" : "fig-traces";
  for (const auto& e : r.figures.exposure)
    if (e.metric == metric) source = "fig-exposure-" + metric;
  return source;
}

// H1, condition x exposure per strategy for one metric, each finding warned about the scored
// trials left out for want of a strategy label.
std::vector<Finding> metric_exposure_findings(const StudyResults& r, const tables::MetricSpec& m,
                                              const std::vector<std::string>& conditions_order,
                                              const WordingRules& rules) {
  const std::string source = exposure_source(r, m.column);
  ExposureInput in;
  std::vector<Finding> fs;
  try {
    in = exposure_input(r.scores, r.figures.labels, m.column);
    // The report's exposure table when the analysis made one (the findings link to it), else
    // fitted here from the labels.
    const tables::ExposureTable* table = nullptr;
    for (const auto& t : r.exposure)
      if (t.metric == m.column) table = &t;
    const auto e = table ? table->result
                         : models::exposure_slopes_by_condition(in.participant, in.condition, in.strategy,
                                                                in.exposure, in.y, conditions_order,
                                                                r.table1.options.test.conf_level,
                                                                r.table1.options.bf_prior_r,
                                                                r.design.design == models::ConditionDesign::within);
    fs = exposure_findings(e, rules, table ? "exposure" : source, m.column);
  } catch (const std::exception& e) {
    fs.push_back(exposure_not_computable(m.column, source, e.what()));
  }
  if (in.unlabelled > 0) {
    const std::string w = fmt::format(
        "{} scored trial{} of {} without a strategy in the logs' labels {} left out of the exposure analysis.",
        in.unlabelled, in.unlabelled == 1 ? "" : "s", m.column, in.unlabelled == 1 ? "is" : "are");
    for (auto& f : fs) f.warnings.push_back(w);
  }
  return fs;
}

}  // namespace

void add_exposure_findings(std::vector<Finding>& out, const StudyResults& r,
                           const std::vector<tables::MetricSpec>& metrics, const WordingRules& rules) {
  if (r.figures.labels.empty()) return;
  if (const std::size_t k = r.scores.conditions().size(); k > 2 && !r.comparison) {
    // Two of three or more conditions would be an arbitrary pair: the lab names the pair.
    const std::string why = fmt::format(
        "the slopes compare two conditions and the study has {}; set compare = \"A,B\" to compare a pair", k);
    for (const auto& m : metrics)
      if (r.scores.metric_index(m.column) >= 0) out.push_back(exposure_not_computable(m.column, exposure_source(r, m.column), why.c_str()));
    return;
  }
  std::vector<std::string> conditions_order;
  if (r.model && !r.model->models.empty() && !r.model->models.front().group1.empty())
    conditions_order = {r.model->models.front().group1, r.model->models.front().group2};
  for (const auto& m : metrics) {
    if (r.scores.metric_index(m.column) < 0) continue;
    for (auto& f : metric_exposure_findings(r, m, conditions_order, rules)) out.push_back(std::move(f));
  }
}

}  // namespace detail

tables::ExposureTable exposure_table(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                                     const std::string& metric, const std::vector<std::string>& conditions,
                                     double conf_level, double bf_prior_r, bool paired) {
  const ExposureInput in = exposure_input(scores, labels, metric);
  return {metric, models::exposure_slopes_by_condition(in.participant, in.condition, in.strategy, in.exposure,
                                                       in.y, conditions, conf_level, bf_prior_r, paired)};
}

ExposureInput exposure_input(const io::ScoresTable& scores, const std::vector<TrialLabel>& labels,
                             const std::string& metric) {
  ExposureInput in;
  const int k = scores.metric_index(metric);
  if (k < 0) return in;
  // Exposure over every labelled trial of a participant in a condition (seeing a strategy is the
  // exposure). Between participants that is the participant's trials; within participants each
  // condition's block counts on its own (docs/analysis.md "Exposure within participants").
  std::vector<std::string> lp, ls;
  std::vector<double> li;
  for (const auto& l : labels) {
    lp.push_back(l.participant + '\x1f' + l.condition);
    li.push_back(static_cast<double>(l.iteration));
    ls.push_back(l.strategy);
  }
  const std::vector<double> counts = models::exposure_counts(lp, li, ls);
  std::map<std::tuple<std::string, std::string, long long>, std::size_t> at;
  for (std::size_t i = 0; i < labels.size(); ++i) at[{labels[i].participant, labels[i].condition, labels[i].iteration}] = i;
  for (const auto& rec : scores.records) {
    const auto& v = rec.values[static_cast<std::size_t>(k)];
    if (!v || std::isnan(*v)) continue;
    const auto it = at.find({rec.participant, rec.condition, rec.iteration});
    if (it == at.end() || labels[it->second].strategy.empty()) {
      ++in.unlabelled;
      continue;
    }
    in.participant.push_back(rec.participant);
    in.condition.push_back(rec.condition);
    in.strategy.push_back(labels[it->second].strategy);
    in.exposure.push_back(counts[it->second]);
    in.y.push_back(*v);
  }
  return in;
}

}  // namespace feint::analysis
