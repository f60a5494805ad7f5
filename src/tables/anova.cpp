// The mixed ANOVA table's numbers: scores -> one mixed ANOVA (and estimated marginal means) per
// metric (see feint/tables/anova.hpp); its renderings are in anova_render.cpp.
#include "feint/tables/anova.hpp"

#include <string>
#include <utility>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/within_anova.hpp"

namespace feint::tables {

std::vector<models::Observation> observations(const io::ScoresTable& scores,
                                              const std::string& metric) {
  const int m = scores.metric_index(metric);
  std::vector<models::Observation> out;
  if (m < 0) return out;
  out.reserve(scores.records.size());
  for (const auto& r : scores.records) {
    out.push_back(
        {r.participant, r.condition, r.iteration, r.values[static_cast<std::size_t>(m)], r.line});
  }
  return out;
}

AnovaReport build_anova_report(const io::ScoresTable& scores,
                               models::SphericityCorrection correction,
                               bool drop_empty_conditions, const AnovaEmmOptions& emm,
                               bool condition_within) {
  AnovaReport report;
  report.source = scores.path;
  report.correction = correction;
  report.emm_options = emm;
  if (condition_within && emm.any())
    throw UsageError("--emmeans with conditions within participants is not supported yet");
  for (const auto& metric : scores.metrics) {
    const auto obs = observations(scores, metric);
    if (condition_within) {  // every participant in every condition: no condition is dropped
      report.analyses.push_back(
          models::within_anova(models::make_within_design(obs, metric, scores.path), correction));
      report.emm.emplace_back();
      continue;
    }
    const models::WideDesign d =
        models::make_wide_design(obs, metric, scores.path, drop_empty_conditions);
    report.analyses.push_back(models::mixed_anova(d, correction));
    std::vector<models::EmmTable> tables;
    if (emm.emmeans)
      for (const auto term :
           {models::EmmTerm::cells, models::EmmTerm::condition, models::EmmTerm::iteration}) {
        if (term != models::EmmTerm::iteration && d.conditions.size() < 2) continue;
        tables.push_back(
            {models::to_string(term), "", models::estimated_means(d, term, emm.conf_level)});
      }
    for (const auto family : emm.families) {
      const bool is_poly = family == models::EmmFamily::poly_iteration ||
                           family == models::EmmFamily::poly_in_condition;
      const bool by_condition = family == models::EmmFamily::pairwise_condition ||
                                family == models::EmmFamily::condition_at_iteration;
      if (d.conditions.size() < 2 && by_condition) continue;
      const models::EmmAdjust adj =
          emm.adjust ? *emm.adjust : (is_poly ? models::EmmAdjust::none : models::EmmAdjust::tukey);
      tables.push_back({models::to_string(family), models::to_string(adj),
                        models::emm_contrasts(d, family, adj, emm.conf_level)});
    }
    report.emm.push_back(std::move(tables));
  }
  return report;
}

}  // namespace feint::tables
