// The all-within repeated-measures ANOVA (condition x iteration within participants) against
// afex::aov_ez(within = c("condition", "iteration")) / car::summary.Anova.mlm
// (tests/golden/models/within_anova_golden.R): SS, df, F, p, GG/HF epsilons and p, Mauchly's W and
// p, afex's MSE, df and p under no, GG and HF correction, ges and pes, on six data sets. Then a
// 2 x 2 example with 3 participants worked by hand (condition F = paired t^2), the one-condition
// case against the one-way mixed ANOVA, and every rejection of make_within_design.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "feint/error.hpp"
#include "feint/models/mixed_anova.hpp"
#include "feint/models/within_anova.hpp"
#include "feint/stats/ttest.hpp"
#include "stats/golden_csv.hpp"

namespace feint::models {
namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

std::map<std::string, std::vector<Observation>> load_sets() {
  std::ifstream in(kDir + "within_anova_data.csv");
  std::map<std::string, std::vector<Observation>> sets;
  std::string line;
  std::getline(in, line);  // header: dataset,participant,condition,iteration,y
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
    sets[f.at(0)].push_back(o);
  }
  return sets;
}

// Closed forms: 1e-10 relative (docs/testing.md); the measured worst is printed on exit.
void expect_rel(std::optional<double> actual, std::optional<double> expected,
                const std::string& what) {
  ASSERT_EQ(actual.has_value(), expected.has_value()) << what;
  if (!expected) return;
  feint::test::record("within ANOVA (afex)", *actual, *expected, what);
  const double tol = 1e-10 * std::max(std::abs(*expected), 1e-300);
  EXPECT_NEAR(*actual, *expected, tol) << what;
}

const AnovaEffect& effect_of(const MixedAnova& a, const std::string& name) {
  for (const auto& e : a.effects)
    if (e.effect == name) return e;
  throw std::runtime_error("no effect " + name);
}

const MauchlyTest* mauchly_of(const MixedAnova& a, const std::string& name) {
  for (const auto& m : a.sphericity)
    if (m.effect == name) return &m;
  return nullptr;
}

// Under `corr`, the reported num df, den df, MSE and p of one golden row (prefix "", gg_, hf_).
void expect_reported(const AnovaEffect& e, const test::GoldenRow& row, const std::string& prefix,
                     const std::string& w) {
  expect_rel(e.report_num_df, row.num(prefix + "num_df"), w + prefix + "num_df");
  expect_rel(e.report_den_df, row.num(prefix + "den_df"), w + prefix + "den_df");
  expect_rel(e.mse, row.num(prefix.empty() ? "MSE" : prefix + "mse"), w + prefix + "MSE");
  expect_rel(e.report_p, row.num(prefix + "p"), w + prefix + "p");
}

TEST(WithinAnovaGolden, AgreesWithAfexAndCarOnEveryDataSet) {
  const auto sets = load_sets();
  ASSERT_EQ(sets.size(), 6u);
  const test::GoldenCsv golden(kDir + "within_anova_golden.csv");
  std::size_t checked = 0, corrected = 0, singular = 0;
  for (const auto& row : golden.rows()) {
    const std::string name = row.str("dataset");
    const WithinDesign d = make_within_design(sets.at(name), "y", name);
    const MixedAnova none = within_anova(d, SphericityCorrection::none);
    const MixedAnova gg = within_anova(d, SphericityCorrection::GG);
    const MixedAnova hf = within_anova(d, SphericityCorrection::HF);
    EXPECT_EQ(static_cast<double>(gg.n_participants), row.number("n")) << name;
    std::string excluded;
    for (const auto& p : gg.excluded) excluded += (excluded.empty() ? "" : ";") + p;
    EXPECT_EQ(excluded, row.str("excluded")) << name;
    const std::string effect = row.str("effect");
    const std::string w = name + " " + effect + " ";
    const AnovaEffect& e = effect_of(none, effect);
    EXPECT_TRUE(e.within) << w;
    expect_rel(e.ss, row.num("ss"), w + "ss");
    expect_rel(e.error_ss, row.num("error_ss"), w + "error_ss");
    expect_rel(e.f, row.num("F"), w + "F");
    expect_rel(e.num_df, row.num("num_df"), w + "uncorrected num_df");
    expect_rel(e.p_value, row.num("p"), w + "uncorrected p");
    expect_reported(e, row, "", w);
    expect_rel(e.ges, row.num("ges"), w + "ges");
    expect_rel(e.pes, row.num("pes"), w + "pes");
    expect_rel(e.gg_eps, row.num("gg_eps"), w + "gg_eps");
    expect_rel(e.hf_eps, row.num("hf_eps"), w + "hf_eps");
    expect_rel(e.p_gg, row.num("p_gg"), w + "p_gg");
    expect_rel(e.p_hf, row.num("p_hf"), w + "p_hf");
    const MauchlyTest* m = mauchly_of(gg, effect);
    expect_rel(m ? m->statistic : std::nullopt, row.num("mauchly_w"), w + "mauchly_w");
    expect_rel(m ? m->p_value : std::nullopt, row.num("mauchly_p"), w + "mauchly_p");
    // A Mauchly entry exactly for the effects with more than one df (empty when E is singular).
    EXPECT_EQ(m != nullptr, e.num_df > 1) << w;
    expect_reported(effect_of(gg, effect), row, "gg_", w);
    expect_reported(effect_of(hf, effect), row, "hf_", w);
    if (row.num("gg_eps") && *row.num("gg_eps") < 0.75) ++corrected;
    if (e.num_df > 1 && !row.num("gg_eps")) {
      ++singular;
      EXPECT_FALSE(effect_of(gg, effect).correction_note.empty()) << w;
      EXPECT_NE(gg.sphericity_note.find(effect), std::string::npos) << w;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 18u);
  EXPECT_GE(corrected, 4u);  // the corrections matter: eps well below 1 in several rows
  EXPECT_EQ(singular, 1u);   // three_participants' interaction: 2 error df for 4 contrasts
}

std::vector<Observation> rows_of(
    const std::vector<std::tuple<std::string, std::string, long long, double>>& rows) {
  std::vector<Observation> out;
  std::uint64_t line = 2;
  for (const auto& [p, c, it, y] : rows) out.push_back({p, c, it, y, line++});
  return out;
}

// 2 conditions x 2 iterations, 3 participants (docs/anova-power.md, "Conditions within
// participants"). Per participant, condition z = (honest sum - deceptive sum) / 2 = -2, -2, -3.5:
// SS = 3 * 2.5^2 = 18.75, E = 1.5, F = 18.75 / (1.5 / 2) = 25; iteration z = -3, -2, -0.5:
// SS = 121/12, E = 19/6, F = 121/19; interaction z = 1, 0, 1.5: SS = 25/12, E = 7/6, F = 25/7;
// participant stratum z = totals / 2 = 6, 8, 8.5: E = 3.5; all errors 28/3.
std::vector<Observation> worked_example() {
  return rows_of({{"P1", "honest", 1, 1},
                  {"P1", "honest", 2, 3},
                  {"P1", "deceptive", 1, 2},
                  {"P1", "deceptive", 2, 6},
                  {"P2", "honest", 1, 2},
                  {"P2", "honest", 2, 4},
                  {"P2", "deceptive", 1, 4},
                  {"P2", "deceptive", 2, 6},
                  {"P3", "honest", 1, 3},
                  {"P3", "honest", 2, 2},
                  {"P3", "deceptive", 1, 5},
                  {"P3", "deceptive", 2, 7}});
}

TEST(WithinAnova, TwoByTwoWithThreeParticipantsWorkedByHand) {
  const auto obs = worked_example();
  const WithinDesign d = make_within_design(obs, "y", "hand.csv");
  ASSERT_EQ(d.n(), 3u);
  EXPECT_EQ(d.conditions, (std::vector<std::string>{"honest", "deceptive"}));
  EXPECT_EQ(d.at(2, 1, 0), 5.0);  // P3, deceptive, iteration 1: cell 1 * 2 + 0
  const MixedAnova a = within_anova(d, SphericityCorrection::GG);
  ASSERT_EQ(a.effects.size(), 3u);
  const AnovaEffect& c = a.effects[0];
  EXPECT_EQ(c.effect, "condition");
  EXPECT_NEAR(c.ss, 18.75, 1e-13);
  EXPECT_NEAR(c.error_ss, 1.5, 1e-13);
  EXPECT_NEAR(c.f, 25.0, 1e-12);
  EXPECT_EQ(c.num_df, 1.0);
  EXPECT_EQ(c.den_df, 2.0);
  EXPECT_NEAR(c.ges, 225.0 / 337.0, 1e-14);
  EXPECT_NEAR(c.pes, 25.0 / 27.0, 1e-14);
  EXPECT_NEAR(c.mse, 0.75, 1e-14);
  EXPECT_NEAR(a.effects[1].f, 121.0 / 19.0, 1e-12);
  EXPECT_NEAR(a.effects[1].ges, 121.0 / 233.0, 1e-14);
  EXPECT_NEAR(a.effects[2].f, 25.0 / 7.0, 1e-12);
  EXPECT_NEAR(a.effects[2].ges, 25.0 / 137.0, 1e-14);
  for (const auto& e : a.effects) {  // one df each: nothing to correct, no Mauchly test
    EXPECT_FALSE(e.gg_eps) << e.effect;
    EXPECT_FALSE(e.report_eps) << e.effect;
    EXPECT_EQ(e.report_p, e.p_value) << e.effect;
  }
  EXPECT_TRUE(a.sphericity.empty());
  // The condition F is the paired t^2 of the participants' condition means, with the same p.
  std::vector<double> honest, deceptive;
  for (std::size_t i = 0; i < d.n(); ++i) {
    honest.push_back((d.at(i, 0, 0) + d.at(i, 0, 1)) / 2);
    deceptive.push_back((d.at(i, 1, 0) + d.at(i, 1, 1)) / 2);
  }
  const auto t = stats::t_test_paired(deceptive, honest);
  EXPECT_NEAR(*t.statistic, 5.0, 1e-13);
  EXPECT_NEAR(c.f, *t.statistic * *t.statistic, 1e-12);
  EXPECT_NEAR(c.p_value, *t.p_value, 1e-13);
}

// One condition: the within ANOVA is the one-way repeated-measures ANOVA of the mixed ANOVA.
TEST(WithinAnova, OneConditionIsTheOneWayRepeatedMeasuresAnova) {
  std::vector<Observation> random;  // the noisiest condition: eps well below 1
  const auto sets = load_sets();  // kept: a range-for over load_sets().at(...) would read a freed map
  for (const auto& o : sets.at("nonspherical"))
    if (o.condition == "random") random.push_back(o);
  const MixedAnova w = within_anova(make_within_design(random, "y", "x"));
  const MixedAnova m = mixed_anova(make_wide_design(random, "y", "x"));
  ASSERT_EQ(w.effects.size(), 1u);
  ASSERT_EQ(w.sphericity.size(), 1u);
  const AnovaEffect &a = w.effects[0], &b = m.effects[0];
  EXPECT_EQ(a.effect, "iteration");
  ASSERT_TRUE(a.gg_eps && b.gg_eps);
  const std::vector<std::pair<double, double>> pairs = {
      {a.ss, b.ss},
      {a.error_ss, b.error_ss},
      {a.f, b.f},
      {a.report_p, b.report_p},
      {a.ges, b.ges},
      {a.pes, b.pes},
      {*a.gg_eps, *b.gg_eps},
      {*a.hf_eps, *b.hf_eps},
      {*w.sphericity[0].statistic, *m.sphericity[0].statistic},
      {*w.sphericity[0].p_value, *m.sphericity[0].p_value}};
  for (const auto& [x, y] : pairs) EXPECT_NEAR(x, y, 1e-12 * std::abs(y));
}

// One iteration, two conditions: only the condition effect, the paired t-test squared.
TEST(WithinAnova, OneIterationIsThePairedTTestOfTheConditions) {
  auto first = worked_example();
  std::erase_if(first, [](const Observation& o) { return o.iteration != 1; });
  const MixedAnova a = within_anova(make_within_design(first, "y", "x"));
  ASSERT_EQ(a.effects.size(), 1u);
  EXPECT_EQ(a.effects[0].effect, "condition");
  // deceptive - honest at iteration 1: 1, 2, 2 -> t = (5/3) / (sqrt(1/3) / sqrt(3)) = 5.
  const auto t = stats::t_test_paired(std::vector<double>{2, 4, 5}, std::vector<double>{1, 2, 3});
  EXPECT_NEAR(*t.statistic, 5.0, 1e-13);
  EXPECT_NEAR(a.effects[0].f, 25.0, 1e-12);
  EXPECT_NEAR(a.effects[0].p_value, *t.p_value, 1e-13);
}

std::string rejection(const std::vector<Observation>& obs) {
  try {
    within_anova(make_within_design(obs, "y", "s.csv"));
  } catch (const InvalidData& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(WithinAnova, RejectsWhatItCannotAnalyse) {
  auto dup = worked_example();
  dup.push_back({"P2", "honest", 2, 9.0, 14});
  EXPECT_NE(rejection(dup).find("s.csv:14: metric 'y': participant 'P2' has a second value for "
                                "condition 'honest' at iteration 2 (the first is on line 7)"),
            std::string::npos)
      << rejection(dup);
  const auto single = rows_of({{"P1", "c", 1, 1}, {"P2", "c", 1, 2}, {"P3", "c", 1, 4}});
  EXPECT_NE(rejection(single).find("one condition ('c') and one iteration (1)"), std::string::npos)
      << rejection(single);
  auto hole = worked_example();  // nobody has deceptive at iteration 2
  std::erase_if(
      hole, [](const Observation& o) { return o.condition == "deceptive" && o.iteration == 2; });
  EXPECT_NE(rejection(hole).find("condition 'deceptive' has no value at iteration 2"),
            std::string::npos)
      << rejection(hole);
  auto incomplete = worked_example();  // each participant misses a different cell
  incomplete[0].value.reset();
  incomplete[5].value.reset();
  incomplete.erase(incomplete.begin() + 11);
  EXPECT_NE(rejection(incomplete).find("0 participant(s) have a value for every one of the 4"),
            std::string::npos)
      << rejection(incomplete);
  auto one = worked_example();
  one[0].value.reset();
  one[5].value.reset();
  EXPECT_NE(rejection(one).find("needs at least two ('P3' is the only one)"), std::string::npos)
      << rejection(one);
  auto constant = worked_example();
  for (auto& o : constant) o.value = 0.5;
  EXPECT_NE(rejection(constant).find("metric 'y' has no variance"), std::string::npos);
  auto additive = worked_example();  // participant + cell effects only: no error left
  for (auto& o : additive)
    o.value = (o.participant == "P2" ? 1.0 : 0.0) + (o.condition == "honest" ? 0.5 : 0.0) +
              0.25 * static_cast<double>(o.iteration);
  EXPECT_NE(rejection(additive).find("no condition x participant variation"), std::string::npos)
      << rejection(additive);
}

TEST(WithinAnova, ExcludesIncompleteParticipantsByName) {
  auto obs = worked_example();
  obs.push_back({"P4", "honest", 1, 2.0, 14});  // P4 has one of the four cells
  obs.push_back({"P5", "honest", 1, std::nullopt, 15});
  const WithinDesign d = make_within_design(obs, "y", "s.csv");
  EXPECT_EQ(d.participants, (std::vector<std::string>{"P1", "P2", "P3"}));
  EXPECT_EQ(d.excluded, (std::vector<std::string>{"P4", "P5"}));
  EXPECT_NEAR(within_anova(d).effects[0].f, 25.0, 1e-12);
}

}  // namespace
}  // namespace feint::models
