// Mixed ANOVA against afex::aov_ez / car::summary.Anova.mlm (tests/golden/models/anova_golden.R):
// every case's SS, df, F, p, GG/HF epsilons and p, Mauchly's W and p, afex's corrected df and MSE,
// ges and pes within 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "feint/models/mixed_anova.hpp"
#include "stats/golden_csv.hpp"
#include "accuracy.hpp"

namespace feint::models {
namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

std::map<std::string, std::vector<Observation>> load_cases() {
  std::ifstream in(kDir + "anova_data.csv");
  std::map<std::string, std::vector<Observation>> cases;
  std::string line;
  std::getline(in, line);  // header: case,participant,condition,iteration,value
  std::uint64_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    const auto f = test::split_commas(line);
    Observation o;
    o.participant = f.at(1);
    o.condition = f.at(2);
    o.iteration = std::stoll(f.at(3));
    if (f.size() > 4 && !f[4].empty()) o.value = std::stod(f[4]);
    o.line = number;
    cases[f.at(0)].push_back(o);
  }
  return cases;
}

void expect_rel(std::optional<double> actual, std::optional<double> expected,
                const std::string& what) {
  ASSERT_EQ(actual.has_value(), expected.has_value()) << what;
  if (!expected) return;
  feint::test::record("mixed ANOVA (afex)", *actual, *expected, what);
  const double tol = 1e-10 * std::max(std::abs(*expected), 1e-300);
  EXPECT_NEAR(*actual, *expected, tol) << what;
}

TEST(MixedAnovaGolden, AgreesWithAfexAndCarOnEveryCase) {
  const auto cases = load_cases();
  ASSERT_EQ(cases.size(), 8u);
  const test::GoldenCsv golden(kDir + "anova_golden.csv");
  std::size_t checked = 0;
  for (const auto& row : golden.rows()) {
    const std::string name = row.str("case");
    const WideDesign d = make_wide_design(cases.at(name), "value", name);
    const MixedAnova gg = mixed_anova(d, SphericityCorrection::GG);
    const MixedAnova hf = mixed_anova(d, SphericityCorrection::HF);
    EXPECT_EQ(static_cast<double>(gg.n_participants), row.number("n")) << name;
    std::string excluded;
    for (const auto& p : gg.excluded) excluded += (excluded.empty() ? "" : ";") + p;
    EXPECT_EQ(excluded, row.str("excluded")) << name;
    const std::string effect = row.str("effect");
    const AnovaEffect* e = nullptr;
    const AnovaEffect* h = nullptr;
    for (std::size_t i = 0; i < gg.effects.size(); ++i) {
      if (gg.effects[i].effect == effect) {
        e = &gg.effects[i];
        h = &hf.effects[i];
      }
    }
    ASSERT_NE(e, nullptr) << name << " " << effect;
    const std::string w = name + " " + effect + " ";
    expect_rel(e->ss, row.num("ss"), w + "ss");
    expect_rel(e->error_ss, row.num("error_ss"), w + "error_ss");
    expect_rel(e->num_df, row.num("num_df"), w + "num_df");
    expect_rel(e->den_df, row.num("den_df"), w + "den_df");
    expect_rel(e->f, row.num("F"), w + "F");
    expect_rel(e->p_value, row.num("p"), w + "p");
    expect_rel(e->gg_eps, row.num("gg_eps"), w + "gg_eps");
    expect_rel(e->hf_eps, row.num("hf_eps"), w + "hf_eps");
    if (e->gg_eps) {  // car leaves 0 in these columns when the matrix is singular
      expect_rel(e->p_gg, row.num("p_gg"), w + "p_gg");
      expect_rel(e->p_hf, row.num("p_hf"), w + "p_hf");
    }
    std::optional<double> mw, mp;
    for (const auto& m : gg.sphericity) {
      if (m.effect == effect) {
        mw = m.statistic;
        mp = m.p_value;
      }
    }
    expect_rel(mw, row.num("mauchly_w"), w + "mauchly_w");
    expect_rel(mp, row.num("mauchly_p"), w + "mauchly_p");
    expect_rel(e->report_num_df, row.num("afex_gg_num_df"), w + "afex GG num df");
    expect_rel(e->report_den_df, row.num("afex_gg_den_df"), w + "afex GG den df");
    expect_rel(e->mse, row.num("afex_gg_mse"), w + "afex GG MSE");
    expect_rel(e->report_p, row.num("afex_gg_p"), w + "afex GG p");
    expect_rel(h->report_den_df, row.num("afex_hf_den_df"), w + "afex HF den df");
    expect_rel(h->report_p, row.num("afex_hf_p"), w + "afex HF p");
    expect_rel(e->ges, row.num("ges"), w + "ges");
    expect_rel(e->pes, row.num("pes"), w + "pes");
    ++checked;
  }
  EXPECT_EQ(checked, 22u);
}

}  // namespace
}  // namespace feint::models
