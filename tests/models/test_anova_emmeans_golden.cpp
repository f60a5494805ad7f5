// Estimated marginal means and contrasts of the repeated-measures ANOVA (complete cases) against
// emmeans 1.8.4 on afex::aov_ez objects with emmeans' default multivariate model
// (tests/golden/models/anova_emm_golden.R): balanced, unbalanced and non-spherical, with
// participants excluded for missing trials, a strong effect, and three unbalanced conditions with
// the pairs of conditions (none, Holm, Tukey).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/models/emmeans.hpp"

#include "golden_csv.hpp"
#include "accuracy.hpp"

namespace {

using namespace feint::models;

const std::string& kDir = feint::test::kModelGoldenDir;

using feint::test::read_csv;

WideDesign design(const std::string& c) {
  std::vector<Observation> obs;
  std::uint64_t line = 1;
  // The strong effect (p-values below 1e-6) has its own file, made by anova_emm_golden.R.
  for (const auto& r : read_csv(kDir + (c == "strong_effect" ? "anova_emm_strong.csv" : "anova_data.csv"))) {
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
      const std::string fam = tukey ? "emmeans on afex, Tukey" : "emmeans on afex";
      for (const char* q : {"estimate", "SE", "lower", "upper", "t", "p"}) {
        if (means && (q[0] == 't' || q[0] == 'p')) continue;
        const double got = q[0] == 'e' ? r.estimate : q[0] == 'S' ? r.std_error : q[0] == 'l' ? r.conf_low
                           : q[0] == 'u' ? r.conf_high : q[0] == 't' ? r.statistic : r.p_value;
        feint::test::record(fam + " " + q, got, g.at(label + "." + q).at(n), w + " " + q);
      }
      // Closed forms (cell means, the pooled covariance, pt): 1e-10 relative, 1e-14 absolute for
      // values at 0 (measured: 9e-13 relative, 6e-15 absolute). Tukey bounds use R's qtukey,
      // which stops at |dq| < 1e-4 but is good to 2e-9 absolute here.
      const auto near = [&](double got, double want, double rel, const char* q, double floor = 1e-14) {
        EXPECT_LE(std::abs(got - want), rel * std::abs(want) + floor)
            << w << " " << q << ": feint " << got << ", R " << want;
      };
      near(r.estimate, g.at(label + ".estimate").at(n), 1e-10, "estimate");
      near(r.std_error, g.at(label + ".SE").at(n), 1e-10, "SE");
      EXPECT_EQ(r.df, g.at(label + ".df").at(n)) << w;
      // With three means R's qtukey is off by up to 1e-8 on the bounds (three_conditions): there
      // the bounds from the root of R's own ptukey are the reference, to 1e-10.
      const bool exact = g.count(label + ".lower_exact") > 0;
      near(r.conf_low, g.at(label + ".lower").at(n), 1e-10, "lower", tukey ? (exact ? 1.5e-8 : 3e-9) : 1e-14);
      near(r.conf_high, g.at(label + ".upper").at(n), 1e-10, "upper", tukey ? (exact ? 1.5e-8 : 3e-9) : 1e-14);
      if (exact) {
        feint::test::record(fam + " bounds (root of ptukey)", r.conf_low, g.at(label + ".lower_exact").at(n), w);
        feint::test::record(fam + " bounds (root of ptukey)", r.conf_high, g.at(label + ".upper_exact").at(n), w);
        near(r.conf_low, g.at(label + ".lower_exact").at(n), 1e-10, "lower (root of ptukey)");
        near(r.conf_high, g.at(label + ".upper_exact").at(n), 1e-10, "upper (root of ptukey)");
      }
      if (!means) {
        near(r.statistic, g.at(label + ".t").at(n), 1e-10, "t");
        // Relative only; R's Tukey p (1 - ptukey) are off by up to 1.3e-11 absolute (a p of
        // 3.9355e-9 given as 3.9287e-9): 2e-11 absolute for those.
        near(r.p_value, g.at(label + ".p").at(n), 1e-10, "p", tukey ? 2e-11 : 0);
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
  if (!g.count("cond_pairs.none.estimate")) return;  // three or more conditions: the pairs of conditions
  cmp("cond_pairs.none", emm_contrasts(d, EmmFamily::pairwise_condition, EmmAdjust::none), false, false, false);
  cmp("cond_pairs.holm", emm_contrasts(d, EmmFamily::pairwise_condition, EmmAdjust::holm), false, false, false);
  cmp("cond_pairs.tukey", emm_contrasts(d, EmmFamily::pairwise_condition, EmmAdjust::tukey), false, false, true);
}

TEST(AnovaEmmeansGolden, BalancedSpherical) { check("balanced_spherical"); }
TEST(AnovaEmmeansGolden, UnbalancedNonSpherical) { check("unbalanced_nonspherical"); }
TEST(AnovaEmmeansGolden, ParticipantsExcludedForMissingTrials) { check("missing_trials"); }
TEST(AnovaEmmeansGolden, StrongEffectWithPValuesBelowOneInAMillion) { check("strong_effect"); }
// 5, 8 and 6 participants in three conditions with unequal variances: the pairs of conditions too,
// unadjusted, Holm and Tukey.
TEST(AnovaEmmeansGolden, ThreeConditionsUnbalancedWithTheirPairs) { check("three_conditions"); }

}  // namespace
