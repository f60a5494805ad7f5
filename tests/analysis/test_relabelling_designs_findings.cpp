// The models' findings of a within study use relabelling p-values that swap the conditions within
// participants (docs/findings.md, "Mixed models: relabelling p-values"), not the models' own
// p-values with a warning: the p of each finding is the one relabel_condition_tests gives on the
// model's own trials with options.within, and the Holm step runs on them.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "feint/analysis/analyze.hpp"
#include "feint/models/model_relabelling.hpp"
#include "feint/stats/p_adjust.hpp"

using namespace feint;

namespace {

const analysis::Finding* by_id(const std::vector<analysis::Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

TEST(RelabellingDesignsFindings, AWithinStudysModelTestsAreRelabelledWithinParticipants) {
  analysis::AnalysisSettings s;  // as data/demo-within/feint.toml
  s.design = "within";
  s.compare = "adaptive,random";
  s.scoring.norm = "raw";
  s.metrics = {"error=0.5", "confusion=0.95@raw"};
  const auto r = analysis::analyze(analysis::load_study(std::string(FEINT_SOURCE_DIR) + "/data/demo-within", s), "test");
  ASSERT_TRUE(r.model && r.trend_model);
  for (const std::string metric : {"error", "confusion"}) {
    SCOPED_TRACE(metric);
    const tables::MetricModel* fm = nullptr;
    for (const auto& m : r.model->models)
      if (m.metric == metric) fm = &m;
    ASSERT_NE(fm, nullptr);
    models::RelabellingOptions ro;
    ro.within = true;
    const auto rt = models::relabel_condition_tests(fm->data, fm->fit.group_levels, ro);
    const std::vector<const analysis::Finding*> family = {by_id(r.findings, "H1-model-interaction-" + metric),
                                                          by_id(r.findings, "H1-model-condition-" + metric),
                                                          by_id(r.findings, "H1-model-trend-" + metric)};
    const std::vector<std::optional<double>> p = {rt.p_interaction, rt.p_condition, rt.p_slope_difference};
    const auto adj = stats::p_adjust(p, stats::PAdjustMethod::holm);
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_NE(family[k], nullptr);
      const auto& f = *family[k];
      for (const auto& w : f.warnings) EXPECT_EQ(w.find("not on relabelling"), std::string::npos) << w;
      EXPECT_NE(f.sentence.find("conditions swapped within participants"), std::string::npos) << f.sentence;
      ASSERT_TRUE(f.p_adjusted && adj[k]);
      EXPECT_DOUBLE_EQ(*f.p_adjusted, *adj[k]) << f.sentence;
    }
  }
}

}  // namespace
