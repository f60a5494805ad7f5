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
#include "accuracy.hpp"

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

// The fit is iterative: what the exact-derivative optimum reaches against lme4's (nloptwrap at
// 1e-14/1e-15 in kr_emm_golden.R). Measured: SE and df within 2.4e-8 relative, p 1.6e-7 (a p of
// 1e-10: a small p magnifies the error of t), estimates 5.1e-10 and bounds 1.3e-9 absolute,
// t 1.5e-8 absolute.
constexpr double kRel = 5e-8, kRelP = 2e-7, kEstimate = 1e-9, kBound = 2e-9;
// R's ptukey computes the upper tail as 1 - P: its Tukey p are off by up to 3.6e-10 absolute
// (a p of 1.5e-11 given as 3.7e-10, strong_effect), so Tukey p are checked against R to 1e-9
// absolute, and against the exact bracket p <= p_Tukey <= m p (Bonferroni) to the last bit.
constexpr double kTukeyPAbs = 1e-9;

void near_rel(double got, double want, const std::string& what, double tol = kRel) {
  feint::test::record((what.find(".tukey") != std::string::npos ? "emmeans on lmer, Tukey" : "emmeans on lmer") +
                          what.substr(what.rfind(' ')),
                      got, want, what);
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
    for (const char* q : {".lower", ".upper", ".t", est.c_str()}) {
      if (!means && q[1] == 't' && q[2] == 0) {
        feint::test::record("emmeans on lmer t", r.statistic, g.at(label + q).at(name), w + " t");
      } else if (q[1] == 'l' || q[1] == 'u') {
        feint::test::record(tukey ? "emmeans on lmer, Tukey CI" : "emmeans on lmer CI",
                            q[1] == 'l' ? r.conf_low : r.conf_high, g.at(label + q).at(name), w + q);
      } else if (q[1] == 'e') {
        feint::test::record("emmeans on lmer estimate", r.estimate, g.at(label + q).at(name), w + q);
      }
    }
    EXPECT_NEAR(r.estimate, g.at(label + est).at(name), kEstimate) << w;
    near_rel(r.std_error, g.at(label + ".SE").at(name), w + " SE");
    near_rel(r.df, g.at(label + ".df").at(name), w + " df");
    // R's qtukey stops at |dq| < 1e-4; on these goldens its Tukey bounds are as good as the rest.
    EXPECT_NEAR(r.conf_low, g.at(label + ".lower").at(name), kBound) << w;
    EXPECT_NEAR(r.conf_high, g.at(label + ".upper").at(name), kBound) << w;
    if (!means) {
      // t near 0 (a contrast of ~1e-6): relative to max(|t|, 1).
      EXPECT_NEAR(r.statistic, g.at(label + ".t").at(name), 1e-8 * std::max(1.0, std::abs(r.statistic))) << w;
      const double want_p = g.at(label + ".p").at(name);
      feint::test::record(tukey ? "emmeans on lmer, Tukey p" : "emmeans on lmer p", r.p_value, want_p, w);
      if (tukey) {
        EXPECT_NEAR(r.p_value, want_p, kRelP * want_p + kTukeyPAbs) << w << " p";
      } else {
        EXPECT_LE(std::abs(r.p_value - want_p), kRelP * want_p) << w << " p: got " << r.p_value << ", R " << want_p;
      }
    }
  }
}

// The exact bracket of a Tukey p (independent of R): the unadjusted p <= p_Tukey <= m p, m the
// contrasts of its family (Bonferroni).
void expect_tukey_bracket(const std::vector<EmmRow>& none, const std::vector<EmmRow>& tukey) {
  ASSERT_EQ(none.size(), tukey.size());
  std::map<std::string, double> m;
  for (const auto& r : none) m[r.by] += 1;
  for (std::size_t i = 0; i < none.size(); ++i) {
    EXPECT_GE(tukey[i].p_value, none[i].p_value * (1 - 1e-12)) << tukey[i].label << " " << tukey[i].by;
    EXPECT_LE(tukey[i].p_value, std::min(1.0, m[none[i].by] * none[i].p_value) * (1 + 1e-12))
        << tukey[i].label << " " << tukey[i].by;
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
  if (with_tukey) {
    for (const EmmFamily f : {EmmFamily::iteration_in_condition, EmmFamily::pairwise_iteration})
      expect_tukey_bracket(emm_contrasts(fit, f, EmmAdjust::none), emm_contrasts(fit, f, EmmAdjust::tukey));
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
// p-values down to 3e-15 (the other cases' are all above 0.029).
TEST(EmmeansGolden, StrongEffectSatterthwaite) { check_case("strong_effect", DdfMethod::satterthwaite, true); }
TEST(EmmeansGolden, StrongEffectKenwardRoger) { check_case("strong_effect", DdfMethod::kenward_roger, true); }

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
