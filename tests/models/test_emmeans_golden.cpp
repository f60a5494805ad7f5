// Estimated marginal means and contrasts of the mixed model against emmeans 1.8.4 on lmer
// (tests/golden/models/kr_emm_golden.R) with lmer.df = "satterthwaite" and "kenward-roger":
// balanced, unbalanced with missing trials, and a participant with a single trial.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/models/mixed_model.hpp"

#include "golden_csv.hpp"

namespace {

using namespace feint::models;

const std::string& kDir = feint::test::kModelGoldenDir;

using feint::test::read_csv;


using Golden = std::map<std::string, std::map<std::string, std::map<std::string, double>>>;
const Golden& golden() {
  static const Golden g = [] {
    Golden m;
    for (const auto& r : read_csv(kDir + "kr_emm_golden.csv"))
      if (r.size() == 5 && r[0] != "case") m[r[0] + "|" + r[1]][r[2]][r[3]] = std::stod(r[4]);
    return m;
  }();
  return g;
}

void near_rel(double got, double want, const std::string& what, double tol = 1e-6) {
  EXPECT_LE(std::abs(got - want) / std::max(std::abs(want), 1e-10), tol)
      << what << ": got " << got << ", R " << want;
}

void check_rows(const std::map<std::string, std::map<std::string, double>>& g,
                const std::string& label, const std::vector<EmmRow>& rows, bool means,
                bool tukey = false) {
  const std::string est = means ? ".emmean" : ".estimate";
  ASSERT_EQ(rows.size(), g.at(label + est).size()) << label;
  for (const auto& r : rows) {
    const std::string name = r.by.empty() ? r.label : r.label + "|" + r.by;
    const std::string w = label + " " + name;
    ASSERT_TRUE(g.at(label + est).count(name)) << w;
    ASSERT_TRUE(r.computed) << w;
    EXPECT_NEAR(r.estimate, g.at(label + est).at(name), 1e-8) << w;
    near_rel(r.std_error, g.at(label + ".SE").at(name), w + " SE");
    near_rel(r.df, g.at(label + ".df").at(name), w + " df");
    // R's qtukey stops at |dq| < 1e-4: Tukey intervals agree to that (feint's are exact).
    const double ci_tol = tukey ? 1e-4 * r.std_error : 1e-7;
    EXPECT_NEAR(r.conf_low, g.at(label + ".lower").at(name), ci_tol) << w;
    EXPECT_NEAR(r.conf_high, g.at(label + ".upper").at(name), ci_tol) << w;
    if (!means) {
      // t near 0 (a contrast of ~1e-6): relative to max(|t|, 1).
      EXPECT_NEAR(r.statistic, g.at(label + ".t").at(name), 1e-6 * std::max(1.0, std::abs(r.statistic))) << w;
      near_rel(r.p_value, g.at(label + ".p").at(name), w + " p");
    }
  }
}

void check_case(const std::string& c, DdfMethod ddf, bool with_tukey) {
  const std::string key = c + "|" + (ddf == DdfMethod::kenward_roger ? "Kenward-Roger" : "Satterthwaite");
  const auto& g = golden().at(key);
  ModelSpec spec;
  spec.ddf = ddf;
  const MixedModelFit fit = fit_mixed_model(feint::test::load_lmm(c), spec, true);
  check_rows(g, "cells", estimated_means(fit, EmmTerm::cells), true);
  check_rows(g, "condition", estimated_means(fit, EmmTerm::condition), true);
  check_rows(g, "iteration", estimated_means(fit, EmmTerm::iteration), true);
  check_rows(g, "cond_by_it", emm_contrasts(fit, EmmFamily::condition_at_iteration, EmmAdjust::none), false);
  for (const auto& [name, adj] : std::vector<std::pair<std::string, EmmAdjust>>{
           {"none", EmmAdjust::none}, {"holm", EmmAdjust::holm}, {"tukey", EmmAdjust::tukey}}) {
    if (adj == EmmAdjust::tukey && !with_tukey) continue;  // qtukey per contrast is slow-ish
    check_rows(g, "it_by_cond." + name, emm_contrasts(fit, EmmFamily::iteration_in_condition, adj),
               false, adj == EmmAdjust::tukey);
    check_rows(g, "iteration." + name, emm_contrasts(fit, EmmFamily::pairwise_iteration, adj),
               false, adj == EmmAdjust::tukey);
  }
  check_rows(g, "poly_by_cond", emm_contrasts(fit, EmmFamily::poly_in_condition, EmmAdjust::none), false);
  check_rows(g, "poly", emm_contrasts(fit, EmmFamily::poly_iteration, EmmAdjust::none), false);
}

TEST(EmmeansGolden, BalancedSatterthwaite) { check_case("balanced5", DdfMethod::satterthwaite, true); }
TEST(EmmeansGolden, BalancedKenwardRoger) { check_case("balanced5", DdfMethod::kenward_roger, false); }
TEST(EmmeansGolden, UnbalancedSatterthwaite) { check_case("unbalanced4_missing", DdfMethod::satterthwaite, false); }
TEST(EmmeansGolden, UnbalancedKenwardRoger) { check_case("unbalanced4_missing", DdfMethod::kenward_roger, true); }
TEST(EmmeansGolden, SingleTrialParticipantSatterthwaite) { check_case("single_trial", DdfMethod::satterthwaite, false); }
TEST(EmmeansGolden, SingleTrialParticipantKenwardRoger) { check_case("single_trial", DdfMethod::kenward_roger, false); }

TEST(Emmeans, PolynomialContrastsAreEmmeansIntegers) {
  EXPECT_EQ(poly_contrasts(4), (std::vector<std::vector<double>>{
                                   {-3, -1, 1, 3}, {1, -1, -1, 1}, {-1, 3, -3, 1}}));
  EXPECT_EQ(poly_contrasts(5)[3], (std::vector<double>{1, -4, 6, -4, 1}));
  EXPECT_EQ(poly_contrasts(20).size(), 6u);
}

TEST(Emmeans, RejectsTrendTukeyOnPolyAndBadAdjust) {
  ModelSpec trend;
  trend.time_scale = TimeScale::linear;
  const MixedModelFit f = fit_mixed_model(feint::test::load_lmm("balanced5"), trend, true);
  EXPECT_THROW(estimated_means(f, EmmTerm::cells), feint::UsageError);
  const MixedModelFit g = fit_mixed_model(feint::test::load_lmm("balanced5"), ModelSpec{}, true);
  EXPECT_THROW(emm_contrasts(g, EmmFamily::poly_iteration, EmmAdjust::tukey), feint::UsageError);
  EXPECT_THROW(parse_emm_adjust("scheffe"), feint::UsageError);
}

}  // namespace
