// H1 findings from the mixed models (condition x iteration, the linear trend) and from condition x
// exposure per strategy: on the demo (the numbers equal the model tables' numbers) and on
// simulated studies with a planted truth. Wording rules: docs/findings.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/binomial.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "feint/analysis/analyze.hpp"
#include "feint/stats/proportions.hpp"
#include "feint/analysis/study_findings.hpp"
#include "feint/models/exposure.hpp"
#include "feint/models/model_relabelling.hpp"
#include "feint/tables/model.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/p_adjust.hpp"

namespace fs = std::filesystem;
using namespace feint;
using analysis::Finding;
using analysis::Strength;

namespace {

const std::string kDemo = std::string(FEINT_SOURCE_DIR) + "/data/demo";

const analysis::StudyResults& demo() {
  static const analysis::StudyResults r = [] {
    analysis::AnalysisSettings s;  // as data/demo/feint.toml
    s.compare = "adaptive,random";
    s.likert.reference = 3.5;
    return analysis::analyze(analysis::load_study(kDemo, s), "test");
  }();
  return r;
}

const Finding* by_id(const std::vector<Finding>& fs, const std::string& id) {
  for (const auto& f : fs)
    if (f.id == id) return &f;
  return nullptr;
}

const tables::MetricModel& metric_model(const tables::ModelAnalysis& a, const std::string& metric) {
  for (const auto& m : a.models)
    if (m.metric == metric) return m;
  throw std::runtime_error("no model of " + metric);
}

const models::AnovaTerm& term(const tables::MetricModel& m, const std::string& name) {
  for (const auto& t : m.fit.anova)
    if (t.term == name) return t;
  throw std::runtime_error("no term " + name);
}

std::string p_text(double p) {
  if (p < 0.001) return "p < .001";
  std::string s = fmt::format("{:.3f}", p);
  return "p = " + (s.rfind("0.", 0) == 0 ? s.substr(1) : s);
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The rule for a test without a Bayes factor, restated: a difference only from the corrected p.
void expect_rule(const Finding& f, double p_adjusted) {
  if (p_adjusted < 0.05) {
    EXPECT_EQ(f.strength, Strength::evidence_for_difference) << f.sentence;
  } else {
    EXPECT_EQ(f.strength, Strength::no_evidence_either_way) << f.sentence;
    EXPECT_TRUE(contains(f.sentence, "not evidence for no difference")) << f.sentence;
  }
  EXPECT_NE(f.strength, Strength::evidence_for_no_difference);
  EXPECT_TRUE(contains(f.sentence, "no Bayes factor")) << f.sentence;
}

}  // namespace

TEST(StudyFindings, DemoMixedModelFindingsCarryTheModelTablesNumbers) {
  const auto& r = demo();
  ASSERT_TRUE(r.model && r.trend_model);
  for (const std::string metric : {"error", "confusion"}) {
    const auto& m = metric_model(*r.model, metric);
    const auto& tm = metric_model(*r.trend_model, metric);
    const auto& inter = term(m, "condition:iteration");
    const auto& cond = term(m, "condition");
    // The trend model's slope difference: the fixed effect condition<2nd level>:iteration.
    const auto& fit = tm.fit;
    ASSERT_EQ(fit.group_levels.size(), 2u);
    const std::string name = "condition" + fit.group_levels[1] + ":iteration";
    const auto idx = std::find(fit.coef_names.begin(), fit.coef_names.end(), name) - fit.coef_names.begin();
    ASSERT_LT(static_cast<std::size_t>(idx), fit.coef_names.size());
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    L(idx) = 1;
    const auto c = models::contrast(fit, L, 0.95);
    // Invariant: the trend model's 1-df interaction F is the square of the slope difference's t.
    EXPECT_NEAR(term(tm, "condition:iteration").f, *c.test.statistic * *c.test.statistic, 1e-8 * inter.f + 1e-10);
    // The relabelling p-values of the three tests (the models' trials, both conditions), then Holm
    // over them, by hand.
    models::LongData d;
    const int k = r.scores.metric_index(metric);
    for (const auto& rec : r.scores.records)
      if (const auto& v = rec.values[static_cast<std::size_t>(k)]) {
        d.participant.push_back(rec.participant);
        d.group.push_back(rec.condition);
        d.time.push_back(static_cast<double>(rec.iteration));
        d.y.push_back(*v);
      }
    models::RelabellingOptions ro;
    ro.permutations = analysis::kModelPermutations;
    const auto rt = models::relabel_condition_tests(d, fit.group_levels, ro);
    // At most 10,000 labellings (the observed one and 9,999 drawn); each test's sequential
    // p-value stops once 50 drawn ones reach its statistic: p = 50 / drawn, else (reached + 1) / 10,000.
    EXPECT_FALSE(rt.exact);
    EXPECT_EQ(rt.exceedances, 50u);
    EXPECT_EQ(rt.labellings, std::max({rt.labellings_interaction, rt.labellings_condition, rt.labellings_slope}));
    EXPECT_LE(rt.labellings, 10000u);
    EXPECT_NEAR(*rt.interaction_f, inter.f, 1e-6 * inter.f);
    EXPECT_NEAR(*rt.condition_f, cond.f, 1e-6 * cond.f);
    EXPECT_NEAR(*rt.slope_difference_t, *c.test.statistic, 1e-6);
    const std::vector<std::optional<double>> ps = {rt.p_interaction, rt.p_condition, rt.p_slope_difference};
    const auto adj = stats::p_adjust(ps, stats::PAdjustMethod::holm);
    auto comma = [](std::uint64_t n) { return n < 1000 ? fmt::format("{}", n) : fmt::format("{},{:03}", n / 1000, n % 1000); };
    auto relabelled = [&](const std::optional<double>& p, std::uint64_t n, bool stopped) {
      EXPECT_DOUBLE_EQ(*p, stopped ? 50.0 / static_cast<double>(n - 1) : std::round(*p * 10000) / 10000) << metric;
      if (!stopped) {
        EXPECT_EQ(n, 10000u) << metric;
      }
      return "relabelling " + p_text(*p) +
             (stopped ? fmt::format(" (sequential: 50 of {} labellings of the participants drawn at random reached "
                                    "the statistic)", comma(n - 1))
                      : " over 10,000 labellings of the participants drawn at random") +
             "; Holm-adjusted";
    };

    const Finding* fi = by_id(r.findings, "H1-model-interaction-" + metric);
    const Finding* fc = by_id(r.findings, "H1-model-condition-" + metric);
    const Finding* ft = by_id(r.findings, "H1-model-trend-" + metric);
    ASSERT_TRUE(fi && fc && ft) << metric;
    // The F statistics are the model table's terms (F, df, p) with the findings' df (whole df
    // without a decimal: docs/findings.md "Degrees of freedom"), in the table and in the sentence.
    const std::string table = tables::render_model(*r.model, tables::OutputFormat::markdown);
    EXPECT_EQ(fi->statistics, tables::anova_apa(inter));
    EXPECT_EQ(fc->statistics, tables::anova_apa(cond));
    EXPECT_EQ(fc->statistics.find(".0) ="), std::string::npos) << fc->statistics;
    EXPECT_TRUE(contains(fi->sentence, fi->statistics));
    EXPECT_TRUE(contains(fi->sentence, fmt::format("{:.2f}", inter.f)));
    EXPECT_TRUE(contains(table, fmt::format("{:.2f}", inter.f))) << table.substr(0, 600);
    EXPECT_TRUE(contains(fi->sentence, "Holm-adjusted over the 3 model tests of " + metric + ": " + p_text(*adj[0])))
        << fi->sentence;
    EXPECT_TRUE(contains(fc->sentence, p_text(*adj[1]))) << fc->sentence;
    EXPECT_TRUE(contains(fi->sentence, relabelled(rt.p_interaction, rt.labellings_interaction, rt.stopped_interaction))) << fi->sentence;
    EXPECT_TRUE(contains(fc->sentence, relabelled(rt.p_condition, rt.labellings_condition, rt.stopped_condition))) << fc->sentence;
    EXPECT_TRUE(contains(ft->sentence, relabelled(rt.p_slope_difference, rt.labellings_slope, rt.stopped_slope))) << ft->sentence;
    expect_rule(*fi, *adj[0]);
    // The condition effect has a Bayes factor (a Welch t test on the participants' mean scores) and
    // the rule of every test with one: a difference needs the corrected p and BF10 >= 3.
    ASSERT_TRUE(fc->bf10) << fc->bf_note;
    EXPECT_TRUE(contains(fc->sentence, "Welch t test on the participants' mean scores")) << fc->sentence;
    if (*adj[1] < 0.05 && *fc->bf10 >= 3)
      EXPECT_EQ(fc->strength, Strength::evidence_for_difference) << fc->sentence;
    else if (1 / *fc->bf10 >= 3)
      EXPECT_EQ(fc->strength, Strength::evidence_for_no_difference) << fc->sentence;
    else
      EXPECT_EQ(fc->strength, Strength::no_evidence_either_way) << fc->sentence;
    EXPECT_EQ(fi->source, "model");
    EXPECT_EQ(ft->source, "model-trend");
    // The slope difference and its interval: the trend table's fixef row (CSV, full precision).
    EXPECT_TRUE(contains(ft->sentence, fmt::format("b = {:.4f} per iteration, 95% CI [{:.4f}, {:.4f}]",
                                                   *c.test.estimate, *c.test.conf_low, *c.test.conf_high)))
        << ft->sentence;
    const std::string csv = tables::render_model(*r.trend_model, tables::OutputFormat::csv);
    EXPECT_TRUE(contains(csv, name)) << csv.substr(0, 400);
    expect_rule(*ft, *adj[2]);
  }
  // On the demo the conditions' error courses differ (the planted adaptive-vs-random effect).
  const Finding* fe = by_id(r.findings, "H1-model-interaction-error");
  ASSERT_TRUE(fe);
  EXPECT_TRUE(contains(fe->sentence, "Condition \u00d7 iteration interaction of error in the mixed model "
                                     "error ~ condition * iteration + (1 | participant)"))
      << fe->sentence;
}

TEST(StudyFindings, DemoExposureFindingsPerStrategyEqualTheModel) {
  const auto& r = demo();
  ASSERT_FALSE(r.figures.labels.empty()) << r.figures.labels_note;
  // An independent join: the strategy column of scores.csv, read back by tables::load_strategies.
  const fs::path dir = fs::temp_directory_path() / fmt::format("feint-sf-{}", ::testing::UnitTest::GetInstance()->random_seed());
  fs::create_directories(dir);
  const fs::path file = dir / "scores.csv";
  { std::ofstream(file) << r.scores_csv; }
  io::ScoresOptions so;
  so.metrics = {"error"};
  const io::ScoresTable scores = io::load_scores(file.string(), so);
  const auto strategy = tables::load_strategies(scores, so);
  fs::remove_all(dir);
  std::vector<std::string> part, cond;
  std::vector<double> it, y;
  for (const auto& rec : scores.records) {
    part.push_back(rec.participant);
    cond.push_back(rec.condition);
    it.push_back(static_cast<double>(rec.iteration));
    y.push_back(rec.values[0].value_or(std::nan("")));
  }
  const auto exposure = models::exposure_counts(part, it, strategy);
  const auto e = models::exposure_slopes_by_condition(part, cond, strategy, exposure, y, {"adaptive", "random"});
  ASSERT_FALSE(e.differences.empty());
  const auto adj = [&] {
    std::vector<std::optional<double>> p;
    for (const auto& d : e.differences) p.push_back(d.test.p_value);
    return stats::p_adjust(p, stats::PAdjustMethod::holm);
  }();
  for (std::size_t i = 0; i < e.differences.size(); ++i) {
    const auto& d = e.differences[i];
    const Finding* f = by_id(r.findings, "H1-exposure-error-" + d.strategy);
    ASSERT_TRUE(f) << d.strategy;
    EXPECT_TRUE(contains(f->sentence, fmt::format("difference {:.3f}, 95% CI [{:.3f}, {:.3f}]", *d.test.estimate,
                                                  *d.test.conf_low, *d.test.conf_high)))
        << f->sentence;
    EXPECT_TRUE(contains(f->sentence, fmt::format("adaptive: {:.3f} per exposure", *e.slopes[i].test.estimate)));
    EXPECT_TRUE(contains(f->statistics, "adjusted " + tables::apa_p(*adj[i]))) << f->statistics;
    // the rule of every Welch test with a Bayes factor (docs/findings.md)
    ASSERT_TRUE(d.test.log_bf10.has_value());
    const double bf10 = std::exp(*d.test.log_bf10);
    EXPECT_EQ(f->strength, bf10 >= 3 && *adj[i] < 0.05 ? Strength::evidence_for_difference
                           : 1 / bf10 >= 3             ? Strength::evidence_for_no_difference
                                                       : Strength::no_evidence_either_way);
    EXPECT_EQ(f->source, "exposure");  // the report's condition x exposure table
  }
  // That table holds the same slopes and differences, and renders the Holm-adjusted p.
  const tables::ExposureTable* table = nullptr;
  for (const auto& t : r.exposure)
    if (t.metric == "error") table = &t;
  ASSERT_TRUE(table);
  ASSERT_EQ(table->result.differences.size(), e.differences.size());
  for (std::size_t i = 0; i < e.differences.size(); ++i) {
    EXPECT_NEAR(*table->result.differences[i].test.estimate, *e.differences[i].test.estimate, 1e-12);
    EXPECT_NEAR(*table->result.slopes[i].test.estimate, *e.slopes[i].test.estimate, 1e-12);
  }
  const std::string csv = tables::render_exposure(r.exposure, tables::OutputFormat::csv);
  EXPECT_TRUE(contains(csv, "metric,strategy,condition,estimate,std_error,df,statistic,p_value,p_adjusted"));
  EXPECT_TRUE(contains(csv, "error,exaggerating,adaptive-random,")) << csv;
  const std::string text = tables::render_exposure(r.exposure, tables::OutputFormat::markdown);
  EXPECT_TRUE(contains(text, "Metric: error")) << text;
  EXPECT_TRUE(contains(text, "p Holm")) << text;
}

namespace {

// A simulated study: 2 conditions x n participants x 8 iterations, strategies A/B alternating per
// participant at random; y = 0.4 + slope_adaptive * iteration (adaptive only) + exposure effect
// (random condition, strategy A: -exposure_drop per earlier exposure to A) + participant + noise.
analysis::StudyResults simulated(unsigned seed, double slope_adaptive, double exposure_drop, std::size_t n = 14) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 0.05), person(0, 0.05);
  std::bernoulli_distribution coin(0.5);
  analysis::StudyResults r;
  r.scores.metrics = {"error"};
  r.scores.has_condition = true;
  for (const std::string cond : {"adaptive", "random"}) {
    for (std::size_t p = 0; p < n; ++p) {
      const std::string id = fmt::format("{}{}", cond, p);
      const double u = person(rng);
      int seen_a = 0;
      for (long long it = 1; it <= 8; ++it) {
        const std::string s = coin(rng) ? "A" : "B";
        double y = 0.4 + u + noise(rng);
        if (cond == "adaptive") y += slope_adaptive * static_cast<double>(it);
        if (cond == "random" && s == "A") y -= exposure_drop * seen_a;
        if (s == "A") ++seen_a;
        r.scores.records.push_back({id, cond, it, {y}, 0});
        r.figures.labels.push_back({id, cond, it, s, "v1"});
      }
    }
  }
  r.table1.options.test.conf_level = 0.95;
  tables::ModelOptions o;
  o.metrics = {"error"};
  r.model = tables::build_model_analysis(r.scores, o);
  o.trend = true;
  r.trend_model = tables::build_model_analysis(r.scores, o);
  return r;
}

}  // namespace

TEST(StudyFindings, SimulatedPlantedSlopeDifferenceIsFound) {
  const std::vector<tables::MetricSpec> metrics = {{"error", 0.5}};
  // Planted: the adaptive error rises 0.03 per iteration, the random one is flat.
  const auto planted = simulated(7, 0.03, 0.0);
  const auto fs = analysis::study_findings(planted, metrics);
  const Finding* ft = by_id(fs, "H1-model-trend-error");
  const Finding* fi = by_id(fs, "H1-model-interaction-error");
  ASSERT_TRUE(ft && fi);
  EXPECT_EQ(ft->strength, Strength::evidence_for_difference) << ft->sentence;
  EXPECT_EQ(fi->strength, Strength::evidence_for_difference) << fi->sentence;
  // The estimate (random minus adaptive, the level order) covers the truth -0.03.
  const auto& fit = metric_model(*planted.trend_model, "error").fit;
  EXPECT_EQ(fit.group_levels[1], "random");
  EXPECT_TRUE(contains(ft->sentence, "random minus adaptive")) << ft->sentence;
  Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
  L(static_cast<Eigen::Index>(std::find(fit.coef_names.begin(), fit.coef_names.end(), "conditionrandom:iteration") -
                              fit.coef_names.begin())) = 1;
  const auto c = models::contrast(fit, L, 0.95);
  EXPECT_LT(*c.test.conf_low, -0.03);
  EXPECT_GT(*c.test.conf_high, -0.03);
  EXPECT_NEAR(*c.test.estimate, -0.03, 0.01);
}

// Null studies (no effect anywhere, the participants exchangeable between the conditions): no model
// finding ever claims "evidence for no difference" (no Bayes factor), and a false "evidence for a
// difference" in any of the three model tests is rare. Each finding claims a difference when its
// Holm-adjusted relabelling p is below .05, so "any of the three" needs a raw p below .05 / 3
// (Holm's first step): by Bonferroni its rate is at most 5 %, whatever the tests' dependence. The
// count over 150 studies is then at most Binomial(150, 0.05), asserted <= its 99.9 % quantile, 17
// (11.3 %; measured: 7, the interaction alone in 4). The studies run on two threads (about 23 s
// CPU in all).
TEST(StudyFindings, NullStudiesRarelyClaimAModelDifferenceAndNeverEquivalence) {
  const int studies = 150;
  struct Outcome {
    bool any = false, interaction = false;
    std::vector<std::string> wrong;  // sentences of findings with a strength a null study must not get
  };
  std::vector<Outcome> outcomes(studies);
  auto run = [&](int first) {
    for (int s = first; s < studies; s += 2) {
      const auto null = simulated(100 + static_cast<unsigned>(s), 0.0, 0.0, 8);
      for (const auto& f : analysis::mixed_model_findings(&*null.model, &*null.trend_model)) {
        if (f.strength == Strength::evidence_for_no_difference || f.strength == Strength::not_computable)
          outcomes[static_cast<std::size_t>(s)].wrong.push_back(f.sentence);
        if (f.strength == Strength::evidence_for_difference) {
          outcomes[static_cast<std::size_t>(s)].any = true;
          if (f.id == "H1-model-interaction-error") outcomes[static_cast<std::size_t>(s)].interaction = true;
        }
      }
    }
  };
  std::thread other(run, 1);
  run(0);
  other.join();
  int false_difference = 0, false_interaction = 0;
  for (const auto& o : outcomes) {
    for (const auto& w : o.wrong) ADD_FAILURE() << w;
    false_difference += o.any;
    false_interaction += o.interaction;
  }
  namespace bm = boost::math;
  const double bound = bm::quantile(bm::complement(bm::binomial_distribution<double>(studies, 0.05), 0.001));
  EXPECT_EQ(bound, 17);
  std::printf("%d null studies: a false difference in %d (the interaction in %d); bound %g\n", studies,
              false_difference, false_interaction, bound);
  EXPECT_LE(false_difference, bound) << "of " << studies << " null studies";
}

TEST(StudyFindings, SimulatedExposureEffectInOneConditionIsFound) {
  const std::vector<tables::MetricSpec> metrics = {{"error", 0.5}};
  // Strategy A wears off under random (-0.06 per earlier exposure), not under adaptive.
  const auto r = simulated(11, 0.0, 0.06, 20);
  const auto fs = analysis::study_findings(r, metrics);
  const Finding* fa = by_id(fs, "H1-exposure-error-A");
  const Finding* fb = by_id(fs, "H1-exposure-error-B");
  ASSERT_TRUE(fa && fb);
  EXPECT_EQ(fa->strength, Strength::evidence_for_difference) << fa->sentence;
  EXPECT_NE(fb->strength, Strength::evidence_for_no_difference) << fb->sentence;
  EXPECT_TRUE(contains(fa->sentence, "Holm-corrected over 2 strategies")) << fa->sentence;

  // The join: exposure counts every labelled trial; a scored trial without a label is counted out.
  auto partial = r;
  partial.figures.labels.erase(partial.figures.labels.begin());  // adaptive0, iteration 1
  const auto in = analysis::exposure_input(partial.scores, partial.figures.labels, "error");
  EXPECT_EQ(in.unlabelled, 1u);
  EXPECT_EQ(in.y.size(), partial.scores.records.size() - 1);
  const auto in_full = analysis::exposure_input(r.scores, r.figures.labels, "error");
  ASSERT_EQ(in_full.exposure.size(), r.scores.records.size());
  // Participant adaptive0: exposure counts the earlier trials with the same strategy.
  int a = 0, b = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    const bool is_a = r.figures.labels[i].strategy == "A";
    EXPECT_EQ(in_full.exposure[i], is_a ? a : b) << i;
    (is_a ? a : b) += 1;
  }
  const auto fs_partial = analysis::study_findings(partial, metrics);
  const Finding* fp = by_id(fs_partial, "H1-exposure-error-A");
  ASSERT_TRUE(fp);
  // Only the unlabelled trial (the two-stage test is calibrated: no warning, docs/findings.md).
  ASSERT_EQ(fp->warnings.size(), 1u);
  EXPECT_TRUE(contains(fp->warnings[0], "1 scored trial of error without a strategy")) << fp->warnings[0];
}

TEST(StudyFindings, OneConditionOnlyGivesNoModelFindingButSaysSo) {
  auto r = simulated(3, 0.0, 0.0, 6);
  r.model.reset();
  r.trend_model.reset();
  for (auto& rec : r.scores.records) rec.condition = "adaptive";
  for (auto& l : r.figures.labels) l.condition = "adaptive";
  const auto fs = analysis::study_findings(r, {{"error", 0.5}});
  EXPECT_EQ(by_id(fs, "H1-model-interaction-error"), nullptr);
  const Finding* f = by_id(fs, "H1-exposure-error");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->strength, Strength::not_computable);
  EXPECT_TRUE(contains(f->sentence, "Only one condition ('adaptive')")) << f->sentence;
  EXPECT_TRUE(analysis::mixed_model_findings(nullptr, nullptr).empty());
}

// Without the trials (or with more than two conditions) the family falls back to the models' own
// p-values, and every finding of it says so.
TEST(StudyFindings, ModelTestsWithoutTrialsToRelabelSayTheyUseTheModelsOwnP) {
  const auto& r = demo();
  auto model = *r.model, trend = *r.trend_model;
  for (auto* a : {&model, &trend})
    for (auto& m : a->models) m.data = {};
  const auto fs = analysis::mixed_model_findings(&model, &trend);
  ASSERT_EQ(fs.size(), 6u);
  const auto& inter = term(metric_model(*r.model, "error"), "condition:iteration");
  const auto& cond = term(metric_model(*r.model, "error"), "condition");
  const Finding* fc = by_id(fs, "H1-model-condition-error");
  ASSERT_TRUE(fc);
  EXPECT_FALSE(contains(fc->sentence, "relabelling p")) << fc->sentence;
  ASSERT_FALSE(fc->warnings.empty());
  EXPECT_TRUE(contains(fc->warnings.back(), "Holm-adjusted on the models' own p-values, not on relabelling p-values "
                                            "(the trials were not given to relabel)"))
      << fc->warnings.back();
  // Holm on the model's p: the condition's p (.005) is the smallest of the three, times 3.
  EXPECT_LT(cond.p, inter.p);
  EXPECT_TRUE(contains(fc->sentence, "Holm-adjusted over the 3 model tests of error: " + p_text(3 * cond.p)))
      << fc->sentence;
}

// A boundary fit is said in the findings of its model, and only there. On the demo the confusion
// model is one (R, lme4, on `feint analyze data/demo`'s scores.csv: participant SD 0, isSingular
// TRUE, condition F(1, 1160) = 1.8789, p = .1707), the error model is not (isSingular FALSE).
TEST(StudyFindings, ASingularModelFitIsSaidInItsFindings) {
  const auto& r = demo();
  ASSERT_TRUE(r.model && r.trend_model);
  EXPECT_TRUE(metric_model(*r.model, "confusion").fit.singular);
  EXPECT_FALSE(metric_model(*r.model, "error").fit.singular);
  for (const char* part : {"interaction", "condition", "trend"}) {
    const Finding* c = by_id(r.findings, std::string("H1-model-") + part + "-confusion");
    const Finding* e = by_id(r.findings, std::string("H1-model-") + part + "-error");
    ASSERT_TRUE(c && e) << part;
    ASSERT_EQ(c->warnings.size(), 1u) << part;
    EXPECT_TRUE(contains(c->warnings[0], "is a singular fit: a variance between participants is estimated at (or "
                                         "near) zero"))
        << c->warnings[0];
    EXPECT_TRUE(contains(c->warnings[0], "The relabelling p-value does not rest on that estimate")) << c->warnings[0];
    EXPECT_TRUE(e->warnings.empty()) << part;
  }
}

// The yes/no question of the study folder (questionnaire_yesno.csv, as `feint collect` and
// `feint simulate study` write it) reaches the findings with no setting, with its numbers
// recomputed from the file.
TEST(YesNoFindings, TheDemoComparesItsYesNoQuestionWithFishersTest) {
  const auto& r = demo();
  ASSERT_TRUE(r.yes_no.has_value());
  // data/demo/questionnaire_yesno.csv: 18 of 30 adaptive, 23 of 30 random answered yes.
  ASSERT_EQ(r.yes_no->summaries.size(), 2u);
  EXPECT_EQ(r.yes_no->summaries[0].proportion.x, 18u);
  EXPECT_EQ(r.yes_no->summaries[1].proportion.x, 23u);
  const auto fisher = feint::stats::fisher_exact({18, 30, 23, 30});
  const Finding* f = by_id(r.findings, "H2-yesno-intentional");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->test, "Fisher's exact test");
  EXPECT_EQ(*f->p, *fisher.p_value);
  EXPECT_EQ(f->direction, "adaptive < random");
  ASSERT_TRUE(f->effect_size.has_value());
  EXPECT_EQ(f->effect_size->name, "odds_ratio");
  EXPECT_EQ(f->effect_size->value, *fisher.estimate);
  EXPECT_EQ(f->strength, Strength::no_evidence_either_way);
  EXPECT_NE(f->sentence.find("Intentional (yes/no): adaptive vs random: no evidence either way (yes 60% of 30 vs "
                             "77% of 30; odds ratio 0.46, 95% CI [0.13, 1.59]; Fisher's exact test, p = .267;"),
            std::string::npos)
      << f->sentence;
}
