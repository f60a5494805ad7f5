// Estimated marginal means and contrasts of the repeated-measures ANOVA (complete cases) against
// emmeans 1.8.4 on afex::aov_ez objects with emmeans' default multivariate model
// (tests/golden/models/anova_emm_golden.R): balanced, unbalanced and non-spherical, and with
// participants excluded for missing trials.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/emmeans.hpp"

#include "golden_csv.hpp"

namespace {

using namespace feint::models;

const std::string& kDir = feint::test::kModelGoldenDir;

using feint::test::read_csv;

WideDesign design(const std::string& c) {
  std::vector<Observation> obs;
  std::uint64_t line = 1;
  for (const auto& r : read_csv(kDir + "anova_data.csv")) {
    ++line;
    if (r[0] != c) continue;
    Observation o;
    o.participant = r[1];
    o.condition = r[2];
    o.iteration = std::stoll(r[3]);
    if (r.size() > 4 && !r[4].empty() && r[4] != "NA") o.value = std::stod(r[4]);
    o.line = line;
    obs.push_back(o);
  }
  return make_wide_design(obs, "value", c);
}

// R's names use afex's syntactic iteration levels: X1, "X1 - X2".
std::string r_name(const EmmRow& r, bool iteration_by) {
  std::string label = r.label;
  for (std::size_t p; (p = label.find("iteration")) != std::string::npos;) label.replace(p, 9, "X");
  std::string by = r.by;
  if (iteration_by && !by.empty()) by = "X" + by;
  return by.empty() ? label : label + "|" + by;
}

void check(const std::string& c) {
  std::map<std::string, std::map<std::string, double>> g;
  for (const auto& r : read_csv(kDir + "anova_emm_golden.csv"))
    if (r.size() == 4 && r[0] == c) g[r[1]][r[2]] = std::stod(r[3]);
  const WideDesign d = design(c);
  auto cmp = [&](const std::string& label, const std::vector<EmmRow>& rows, bool it_by,
                 bool means, bool tukey) {
    ASSERT_EQ(rows.size(), g.at(label + ".estimate").size()) << c << " " << label;
    for (EmmRow r : rows) {
      if (means && label == "cells") r.label = r.label.substr(0, r.label.find('|')) + "|X" + r.label.substr(r.label.find('|') + 1);
      if (means && label == "iteration") r.label = "X" + r.label;
      const std::string n = r_name(r, it_by);
      const std::string w = c + " " + label + " " + n;
      ASSERT_TRUE(g.at(label + ".estimate").count(n)) << w;
      EXPECT_NEAR(r.estimate, g.at(label + ".estimate").at(n), 1e-9) << w;
      EXPECT_NEAR(r.std_error, g.at(label + ".SE").at(n), 1e-9) << w;
      EXPECT_EQ(r.df, g.at(label + ".df").at(n)) << w;
      const double ci = tukey ? 1e-4 * r.std_error : 1e-9;
      EXPECT_NEAR(r.conf_low, g.at(label + ".lower").at(n), ci) << w;
      EXPECT_NEAR(r.conf_high, g.at(label + ".upper").at(n), ci) << w;
      if (!means) {
        EXPECT_NEAR(r.statistic, g.at(label + ".t").at(n), 1e-8 * std::max(1.0, std::abs(r.statistic))) << w;
        EXPECT_NEAR(r.p_value, g.at(label + ".p").at(n), 1e-6 * std::max(1e-3, g.at(label + ".p").at(n))) << w;
      }
    }
  };
  cmp("cells", estimated_means(d, EmmTerm::cells), false, true, false);
  cmp("condition", estimated_means(d, EmmTerm::condition), false, true, false);
  cmp("iteration", estimated_means(d, EmmTerm::iteration), false, true, false);
  cmp("cond_by_it", emm_contrasts(d, EmmFamily::condition_at_iteration, EmmAdjust::tukey), true, false, true);
  cmp("it_by_cond.none", emm_contrasts(d, EmmFamily::iteration_in_condition, EmmAdjust::none), false, false, false);
  cmp("it_by_cond.holm", emm_contrasts(d, EmmFamily::iteration_in_condition, EmmAdjust::holm), false, false, false);
  cmp("it_by_cond.tukey", emm_contrasts(d, EmmFamily::iteration_in_condition, EmmAdjust::tukey), false, false, true);
  cmp("poly_by_cond", emm_contrasts(d, EmmFamily::poly_in_condition, EmmAdjust::none), false, false, false);
}

TEST(AnovaEmmeansGolden, BalancedSpherical) { check("balanced_spherical"); }
TEST(AnovaEmmeansGolden, UnbalancedNonSpherical) { check("unbalanced_nonspherical"); }
TEST(AnovaEmmeansGolden, ParticipantsExcludedForMissingTrials) { check("missing_trials"); }

}  // namespace
