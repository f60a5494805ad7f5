// Table 1 with three or more conditions (feint/tables/table1_conditions.hpp) against R: every number
// of tests/golden/table1/table1_conditions_golden.csv (made by table1_conditions_golden.R with
// oneway.test, aov, effectsize, kruskal.test, afex::aov_ez, friedman.test and p.adjust, and the maxF
// family by complete enumeration) on the eight scores files beside it; then the maxF family against
// a brute-force enumeration written here, its seeded sampling, and the renderings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numeric>
#include <string>
#include <tuple>

#include "accuracy.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/scores.hpp"
#include "feint/models/within_anova.hpp"
#include "feint/stats/anova.hpp"
#include "feint/stats/maxf.hpp"
#include "feint/tables/anova.hpp"
#include "feint/tables/table1.hpp"

using namespace feint;

namespace {

const std::string kDir = std::string(FEINT_SOURCE_DIR) + "/tests/golden/table1/";

using Key = std::tuple<std::string, std::string, std::string, std::string>;  // dataset, metric, iteration, quantity

std::map<Key, std::string> read_golden() {
  std::ifstream in(kDir + "table1_conditions_golden.csv");
  std::map<Key, std::string> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[{f.at(0), f.at(1), f.at(2), f.at(3)}] = f.at(4);
  }
  return out;
}

tables::Table1 table(const std::string& file, tables::Table1Options o = {}) {
  io::ScoresOptions so;
  so.metrics = {"error", "confusion"};
  return tables::build_table1(io::load_scores(kDir + file, so), o);
}

tables::Table1Options holm() {
  tables::Table1Options o;
  o.p_adjust = stats::PAdjustMethod::holm;
  return o;
}

const std::vector<std::string> kBetween = {"b3_balanced.csv", "b4_unbalanced.csv", "b3_missing.csv", "b4_ties.csv",
                                           "tiny_between.csv"};
const std::vector<std::string> kWithin = {"w3_within.csv", "w4_within.csv", "tiny_within.csv", "w3_strong.csv",
                                          "w4_missing.csv"};

/// Checks the golden quantities of one dataset; returns how many were compared.
class Checker {
 public:
  Checker(const std::map<Key, std::string>& golden, std::string dataset) : golden_(golden), dataset_(std::move(dataset)) {}

  /// `tolerance` relative (absolute below 1); a golden NA expects no value.
  void operator()(const std::string& metric, long long it, const std::string& quantity, std::optional<double> got,
                  double tolerance = 1e-10) {
    const auto f = golden_.find({dataset_, metric, std::to_string(it), quantity});
    ASSERT_NE(f, golden_.end()) << dataset_ << " " << metric << " " << it << " " << quantity;
    const std::string what = dataset_ + " " + metric + " " + std::to_string(it) + " " + quantity;
    ++checked;
    if (f->second == "NA") {
      EXPECT_FALSE(got.has_value()) << what;
      return;
    }
    ASSERT_TRUE(got.has_value()) << what;
    const double want = std::stod(f->second);
    EXPECT_NEAR(*got, want, tolerance * std::max(1.0, std::fabs(want))) << what;
    test::record(quantity.find("effectsize") != std::string::npos ? "table1 conditions: effectsize's searched bounds"
                 : quantity.find("_low") != std::string::npos   ? "table1 conditions: interval bounds (exact roots)"
                                                                : "table1 conditions: tests",
                 *got, want, what);
  }
  std::size_t checked = 0;

 private:
  const std::map<Key, std::string>& golden_;
  std::string dataset_;
};

std::optional<double> computed(const stats::TestResult& r, std::optional<double> v) {
  return r.computed ? v : std::nullopt;
}

}  // namespace

TEST(Table1Conditions, BetweenParticipantsEveryNumberEqualsR) {
  const auto golden = read_golden();
  std::size_t total = 0;
  for (const auto& file : kBetween) {
    const tables::Table1 t = table(file, holm());
    ASSERT_TRUE(t.conditions.has_value()) << file;
    const auto& c = *t.conditions;
    ASSERT_FALSE(c.within) << file;
    ASSERT_EQ(c.rows.size(), 3 * c.iterations.size() * c.metrics.size());
    Checker check(golden, file);
    for (std::size_t m = 0; m < c.metrics.size(); ++m)
      for (std::size_t i = 0; i < c.iterations.size(); ++i) {
        const auto* row = &c.primary(i, m);
        const std::string& metric = c.metrics[m];
        const long long it = c.iterations[i];
        const auto& w = row[0].row.result;
        ASSERT_EQ(w.test, "welch_anova");
        check(metric, it, "welch_F", computed(w, w.statistic));
        check(metric, it, "welch_df1", computed(w, w.df));
        check(metric, it, "welch_df2", computed(w, w.df2));
        check(metric, it, "welch_p", computed(w, w.p_value));
        check(metric, it, "welch_p_holm", computed(w, w.p_adjusted));
        const auto& a = row[1].row.result;
        ASSERT_EQ(a.test, "anova");
        check(metric, it, "aov_F", a.statistic);
        check(metric, it, "aov_df1", a.df);
        check(metric, it, "aov_df2", a.df2);
        check(metric, it, "aov_p", a.p_value);
        check(metric, it, "eta2", a.r_squared);
        check(metric, it, "eta2_low", a.eta_squared_low, 2e-9);
        check(metric, it, "omega2", row[1].omega_squared);
        check(metric, it, "omega2_low", row[1].omega_squared_low, 2e-9);
        // effectsize's own bounds come from an optim() search: the same quantity, to its precision.
        check(metric, it, "eta2_low_effectsize", a.eta_squared_low, 1e-3);
        check(metric, it, "omega2_low_effectsize", row[1].omega_squared_low, 1e-3);
        EXPECT_EQ(a.eta_squared_high, 1.0);
        EXPECT_EQ(row[1].omega_squared_high, 1.0);
        const auto& k = row[2].row.result;
        ASSERT_EQ(k.test, "kruskal_wallis");
        check(metric, it, "kw_chi2", k.statistic);
        check(metric, it, "kw_df", k.df);
        check(metric, it, "kw_p", k.p_value);
        check(metric, it, "kw_epsilon2", k.rank_epsilon_squared);
      }
    total += check.checked;
  }
  // 5 files: (6 + 5 + 8 + 4 + 3) iterations x 2 metrics x 19 quantities.
  EXPECT_EQ(total, 26u * 2 * 19);
}

TEST(Table1Conditions, WithinParticipantsEveryNumberEqualsR) {
  const auto golden = read_golden();
  std::size_t total = 0;
  for (const auto& file : kWithin) {
    const tables::Table1 t = table(file, holm());
    ASSERT_TRUE(t.conditions.has_value()) << file;
    const auto& c = *t.conditions;
    ASSERT_TRUE(c.within) << file;
    Checker check(golden, file);
    for (std::size_t m = 0; m < c.metrics.size(); ++m)
      for (std::size_t i = 0; i < c.iterations.size(); ++i) {
        const auto* row = &c.primary(i, m);
        const std::string& metric = c.metrics[m];
        const long long it = c.iterations[i];
        const auto& r = row[0].row.result;
        ASSERT_EQ(r.test, "rm_anova");
        ASSERT_TRUE(r.computed) << r.note;
        check(metric, it, "rm_F", r.statistic);
        check(metric, it, "rm_df1", r.df);
        check(metric, it, "rm_df2", r.df2);
        check(metric, it, "rm_p", r.p_value);
        check(metric, it, "rm_p_holm", r.p_adjusted);
        check(metric, it, "rm_ges", row[0].ges);
        // ges's interval as effectsize's eta_squared(generalized = TRUE) on the afex model: the
        // exact root of its definition, and effectsize's own optim() search to its precision.
        check(metric, it, "rm_ges_low", row[0].ges_low, 2e-9);
        check(metric, it, "rm_ges_low_effectsize", row[0].ges_low, 1e-6);
        check(metric, it, "rm_ges_high_effectsize", row[0].ges_high);
        check(metric, it, "rm_gg_eps", row[0].sphericity_epsilon);
        check(metric, it, "rm_n", static_cast<double>(r.n1));
        const auto& f = row[1].row.result;
        ASSERT_EQ(f.test, "friedman");
        check(metric, it, "friedman_chi2", f.statistic);
        check(metric, it, "friedman_df", f.df);
        check(metric, it, "friedman_p", f.p_value);
        check(metric, it, "kendalls_w", row[1].kendalls_w);
      }
    total += check.checked;
  }
  EXPECT_EQ(total, (5u + 4 + 2 + 3 + 4) * 2 * 15);
  // w3: P07 lacks fixed-block at iteration 4 (both metrics), P04 random's error at iteration 2.
  const auto c = *table("w3_within.csv").conditions;
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_NE(c.warnings[0].find("iteration 2: P04; iteration 4: P07"), std::string::npos) << c.warnings[0];
  EXPECT_EQ(c.primary(3, 0).row.result.n1, 10u);
}

TEST(Table1Conditions, MaxFFamilyEqualsCompleteEnumerationInR) {
  const auto golden = read_golden();
  for (const auto& [file, count] : {std::pair<std::string, double>{"tiny_between.csv", 210},
                                   {"tiny_within.csv", 1296}}) {
    const auto c = *table(file).conditions;
    Checker check(golden, file);
    for (std::size_t m = 0; m < c.metrics.size(); ++m) {
      ASSERT_TRUE(c.families[m].note.empty()) << c.families[m].note;
      EXPECT_TRUE(c.families[m].exact);
      EXPECT_EQ(static_cast<double>(c.families[m].labellings),
                std::stod(golden.at({file, c.metrics[m], "NA", "labellings"})));
      EXPECT_EQ(static_cast<double>(c.families[m].labellings), count);
      for (std::size_t i = 0; i < c.iterations.size(); ++i)
        check(c.metrics[m], c.iterations[i], "p_maxf", c.primary(i, m).p_maxf, 1e-12);
    }
    EXPECT_EQ(check.checked, 2 * c.iterations.size());
  }
}

namespace {

/// Westfall & Young's step-down p by its definition: p_(r) = max over r' <= r of the share of
/// labellings whose largest statistic among the tests ranked r' and below reaches F_(r').
std::vector<std::optional<double>> step_down(const std::vector<double>& observed,
                                             const std::vector<std::vector<double>>& labellings) {
  std::vector<std::size_t> order;
  for (std::size_t j = 0; j < observed.size(); ++j)
    if (!std::isnan(observed[j])) order.push_back(j);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return observed[a] > observed[b]; });
  std::vector<std::optional<double>> p(observed.size());
  double running = 0;
  for (std::size_t r = 0; r < order.size(); ++r) {
    const double f = observed[order[r]];
    double reached = 0;
    for (const auto& s : labellings) {
      double u = -HUGE_VAL;
      for (std::size_t q = r; q < order.size(); ++q)
        if (!std::isnan(s[order[q]])) u = std::max(u, s[order[q]]);
      if (u >= f - 1e-9 * std::max(1.0, f)) ++reached;
    }
    running = std::max(running, reached / static_cast<double>(labellings.size()));
    p[order[r]] = running;
  }
  return p;
}

/// metric -> participant -> (condition, iteration) -> value, from a scores file.
struct Cube {
  std::vector<std::string> participants, conditions;
  std::vector<long long> iterations;
  std::map<std::tuple<std::string, std::string, long long>, double> value;
  double at(const std::string& p, const std::string& c, long long it) const {
    const auto f = value.find({p, c, it});
    return f == value.end() ? std::nan("") : f->second;
  }
};

Cube cube(const std::string& file, const std::string& metric) {
  io::ScoresOptions so;
  so.metrics = {metric};
  const auto scores = io::load_scores(kDir + file, so);
  Cube c;
  c.conditions = scores.conditions();
  c.iterations = scores.iterations();
  for (const auto& r : scores.records) {
    if (std::find(c.participants.begin(), c.participants.end(), r.participant) == c.participants.end())
      c.participants.push_back(r.participant);
    if (r.values[0]) c.value[{r.participant, r.condition, r.iteration}] = *r.values[0];
  }
  return c;
}

}  // namespace

// The library's own Welch F (stats::welch_anova) and repeated-measures F (models::within_anova) on
// every relabelling, not the relabelling's fast sums.
TEST(Table1Conditions, MaxFFamilyEqualsBruteForceEnumeration) {
  for (const std::string metric : {"error", "confusion"}) {
    const Cube b = cube("tiny_between.csv", metric);
    std::vector<std::string> label;  // each participant's condition
    for (const auto& p : b.participants)
      for (const auto& c : b.conditions)
        if (b.value.count({p, c, b.iterations[0]}) || b.value.count({p, c, b.iterations[1]})) label.push_back(c);
    ASSERT_EQ(label.size(), 7u);
    auto welch = [&](const std::vector<std::string>& lab) {
      std::vector<double> f;
      for (long long it : b.iterations) {
        std::vector<std::vector<double>> groups(b.conditions.size());
        for (std::size_t i = 0; i < lab.size(); ++i) {
          const auto c = static_cast<std::size_t>(std::find(b.conditions.begin(), b.conditions.end(), lab[i]) -
                                                  b.conditions.begin());
          for (const auto& src : b.conditions)
            if (const double v = b.at(b.participants[i], src, it); !std::isnan(v)) groups[c].push_back(v);
        }
        const auto r = stats::welch_anova(groups);
        f.push_back(r.computed ? *r.statistic : std::nan(""));
      }
      return f;
    };
    std::vector<std::vector<double>> all;
    std::vector<std::string> lab = label;
    std::sort(lab.begin(), lab.end());
    do all.push_back(welch(lab));
    while (std::next_permutation(lab.begin(), lab.end()));
    ASSERT_EQ(all.size(), 210u);
    const auto want = step_down(welch(label), all);
    const auto c = *table("tiny_between.csv").conditions;
    const std::size_t m = metric == "error" ? 0 : 1;
    for (std::size_t i = 0; i < c.iterations.size(); ++i) {
      ASSERT_EQ(c.primary(i, m).p_maxf.has_value(), want[i].has_value()) << metric << " " << i;
      if (want[i]) {
        EXPECT_NEAR(*c.primary(i, m).p_maxf, *want[i], 1e-12) << metric << " " << i;
      }
    }
  }
  for (const std::string metric : {"error", "confusion"}) {
    const Cube w = cube("tiny_within.csv", metric);
    const std::size_t P = w.participants.size(), K = w.conditions.size();
    auto rm = [&](const std::vector<std::vector<std::size_t>>& order) {
      std::vector<double> f;
      for (long long it : w.iterations) {
        models::WithinDesign d;
        d.conditions = w.conditions;
        d.iterations = {it};
        d.participants = w.participants;
        for (std::size_t i = 0; i < P; ++i)
          for (std::size_t c = 0; c < K; ++c) d.y.push_back(w.at(w.participants[i], w.conditions[order[i][c]], it));
        f.push_back(models::within_anova(d, models::SphericityCorrection::none).effects.front().f);
      }
      return f;
    };
    std::vector<std::size_t> identity(K);
    std::iota(identity.begin(), identity.end(), std::size_t{0});
    std::vector<std::vector<std::size_t>> orders;
    std::vector<std::size_t> o = identity;
    do orders.push_back(o);
    while (std::next_permutation(o.begin(), o.end()));
    std::vector<std::vector<double>> all;
    for (std::size_t code = 0; code < 1296; ++code) {
      std::vector<std::vector<std::size_t>> order(P);
      for (std::size_t i = 0, r = code; i < P; ++i, r /= orders.size()) order[i] = orders[r % orders.size()];
      all.push_back(rm(order));
    }
    const auto want = step_down(rm(std::vector<std::vector<std::size_t>>(P, identity)), all);
    const auto c = *table("tiny_within.csv").conditions;
    const std::size_t m = metric == "error" ? 0 : 1;
    for (std::size_t i = 0; i < c.iterations.size(); ++i)
      EXPECT_NEAR(c.primary(i, m).p_maxf.value_or(-1), want[i].value_or(-2), 1e-12) << metric << " " << i;
  }
}

TEST(Table1Conditions, SampledRelabellingsAreSeededAndNearTheExactFamily) {
  tables::Table1Options o;
  o.omnibus_permutations = 999;  // fewer than the 1296 orders: drawn at random
  const auto exact = *table("tiny_within.csv").conditions;
  const auto a = *table("tiny_within.csv", o).conditions;
  const auto again = *table("tiny_within.csv", o).conditions;
  o.omnibus_seed = 7;
  const auto other = *table("tiny_within.csv", o).conditions;
  EXPECT_FALSE(a.families[0].exact);
  EXPECT_EQ(a.families[0].labellings, 1000u);
  bool differs = false;
  for (std::size_t m = 0; m < 2; ++m)
    for (std::size_t i = 0; i < a.iterations.size(); ++i) {
      const double p = *a.primary(i, m).p_maxf, q = *exact.primary(i, m).p_maxf;
      EXPECT_EQ(p, *again.primary(i, m).p_maxf);  // the same seed, the same p on every run
      differs = differs || p != *other.primary(i, m).p_maxf;
      // Within four standard errors of the exact family p (1,000 labellings), and never 0.
      EXPECT_NEAR(p, q, 4 * std::sqrt(q * (1 - q) / 1000) + 1e-3) << m << " " << i;
      EXPECT_GE(p, 1.0 / 1000);
    }
  EXPECT_TRUE(differs);
  // Between participants too: b3_balanced has 24! / (8!)^3 assignments, far more than 9,999.
  const auto b = *table("b3_balanced.csv").conditions;
  EXPECT_FALSE(b.families[0].exact);
  EXPECT_EQ(b.families[0].labellings, 10000u);
  EXPECT_EQ(b.primary(2, 1).p_maxf, table("b3_balanced.csv").conditions->primary(2, 1).p_maxf);
  // The step-down p is never below the test's own p-value over the same labellings' maximum.
  for (std::size_t i = 0; i < b.iterations.size(); ++i) EXPECT_GE(*b.primary(i, 0).p_maxf, 1.0 / 10000);
}

TEST(Table1Conditions, RenderedInEveryFormat) {
  const tables::Table1 t = table("b3_missing.csv", holm());
  const auto& c = *t.conditions;
  const std::string text = tables::render_table1(t, tables::OutputFormat::text);
  for (const char* s : {"Welch's F (primary)", "p maxF", "p adj.", "One-way ANOVA", "Kruskal\u2013Wallis",
                        "\u03c9\u00b2", "Condition: adaptive", "Westfall-Young step-down maxF",
                        "p.adjust(method = \"holm\")", "(read off the data: each of the 23 participants"})
    EXPECT_NE(text.find(s), std::string::npos) << s;
  const std::string latex = tables::render_table1(t, tables::OutputFormat::latex);
  EXPECT_NE(latex.find("\\label{tab:feint-table1-conditions}"), std::string::npos);
  EXPECT_NE(latex.find("\\ensuremath{\\omega}"), std::string::npos);
  EXPECT_EQ(latex.find("\u03c9"), std::string::npos);  // no raw omega for pdflatex to choke on
  EXPECT_EQ(latex.find("\u03b5"), std::string::npos);
  const std::string md = tables::render_table1(t, tables::OutputFormat::markdown);
  EXPECT_NE(md.find("| **Iteration** |"), std::string::npos);
  // CSV: Table 1's rows, then the omnibus rows, with the omnibus columns after Table 1's.
  const std::string csv = tables::render_table1(t, tables::OutputFormat::csv);
  std::vector<std::string> lines;
  for (std::size_t at = 0, nl; (nl = csv.find('\n', at)) != std::string::npos; at = nl + 1)
    lines.push_back(csv.substr(at, nl - at));
  ASSERT_EQ(lines.size(), 1 + t.rows.size() + c.rows.size());
  const auto header = io::split_csv_line(lines[0]);
  const auto extra = tables::table1_conditions_columns();
  ASSERT_EQ(header.size(), tables::kTableColumns.size() + extra.size());
  EXPECT_EQ(header[tables::kTableColumns.size()], "df2");
  const auto p_maxf = static_cast<std::size_t>(std::find(header.begin(), header.end(), "p_maxf") - header.begin());
  const auto first = io::split_csv_line(lines[1 + t.rows.size()]);
  EXPECT_EQ(first[2], "welch_anova");
  EXPECT_EQ(first[6], "adaptive, random, fixed-block");
  EXPECT_EQ(std::stod(first[p_maxf]), *c.rows.front().p_maxf);
  EXPECT_TRUE(io::split_csv_line(lines[1])[p_maxf].empty());  // a one-sample row
  const std::string json = tables::render_table1(t, tables::OutputFormat::json);
  EXPECT_NE(json.find("\"test\": \"kruskal_wallis\""), std::string::npos);
  EXPECT_NE(json.find("\"omega_squared_low\": "), std::string::npos);
  // Within: the repeated-measures columns.
  tables::Table1Options o;
  o.apa = true;
  const std::string within = tables::render_table1(table("w3_within.csv", o), tables::OutputFormat::text);
  for (const char* s : {"Repeated-measures F (primary)", "\u03b5 GG", "Friedman", "F(1.", "\u03c7\u00b2(2) = "})
    EXPECT_NE(within.find(s), std::string::npos) << s;
}

TEST(Table1Conditions, OnlyWithThreeOrMoreConditionsInOneSampleModeWithEveryCondition) {
  EXPECT_FALSE(table("b3_balanced.csv", [] {
                 tables::Table1Options o;
                 o.condition = "random";
                 return o;
               }()).conditions);
  EXPECT_FALSE(table("b3_balanced.csv", [] {
                 tables::Table1Options o;
                 o.compare = std::pair<std::string, std::string>{"adaptive", "random"};
                 return o;
               }()).conditions);
  io::ScoresOptions so;
  so.metrics = {"error"};
  tables::Table1Options o;
  o.metrics = {{"error", 0.5, ""}};
  const auto two = io::load_scores(std::string(FEINT_TEST_DATA_DIR) + "/table/scores_small.csv", so);
  ASSERT_EQ(two.conditions().size(), 2u);
  EXPECT_FALSE(tables::build_table1(two, o).conditions);
}

// Some participants in two conditions, others in one: only the lab knows the design. Table 1 is
// still made, and says why the conditions are not compared; declared, the design is taken.
TEST(Table1Conditions, AnUnclearDesignIsNotComparedAndSaysWhy) {
  const std::string path = testing::TempDir() + "table1_conditions_unclear.csv";
  {
    std::ofstream out(path);
    out << "participant,condition,iteration,error,confusion\n";
    const char* rows[][2] = {{"P1", "a"}, {"P1", "b"}, {"P1", "c"}, {"P2", "a"}, {"P2", "b"}, {"P2", "c"},
                             {"P3", "a"}, {"P3", "b"}, {"P3", "c"}, {"P4", "a"}, {"P4", "b"}};
    int k = 0;
    for (const auto& r : rows)
      for (int it = 1; it <= 2; ++it, ++k) out << r[0] << "," << r[1] << "," << it << "," << 0.4 + 0.037 * (k % 7)
                                               << "," << 0.9 - 0.051 * (k % 5) << "\n";
  }
  io::ScoresOptions so;
  so.metrics = {"error", "confusion"};
  const auto scores = io::load_scores(path, so);
  // P4 saw two of three conditions: read off the data, that is neither design.
  const tables::Table1 t = tables::build_table1(scores, {});
  ASSERT_TRUE(t.conditions.has_value());
  EXPECT_TRUE(t.conditions->rows.empty());
  EXPECT_NE(t.conditions->not_computed.find("participant 'P4' has trials in 2 of the 3 conditions"),
            std::string::npos)
      << t.conditions->not_computed;
  const std::string text = tables::render_table1(t, tables::OutputFormat::text);
  EXPECT_NE(text.find("The conditions are not compared per iteration"), std::string::npos);
  tables::Table1Options o;
  o.design = models::ConditionDesign::within;
  const tables::Table1 w = tables::build_table1(scores, o);
  ASSERT_TRUE(w.conditions->within);
  EXPECT_EQ(w.conditions->primary(0, 0).row.result.n1, 3u);  // P4 has no condition c
  // P5 in one condition beside people in several: models::check_condition_design says why.
  {
    std::ofstream out(path, std::ios::app);
    out << "P5,a,1,0.5,0.8\nP5,a,2,0.6,0.7\n";
  }
  const tables::Table1 u = tables::build_table1(io::load_scores(path, so), {});
  EXPECT_TRUE(u.conditions->rows.empty());
  EXPECT_NE(u.conditions->not_computed.find("'P5'"), std::string::npos) << u.conditions->not_computed;
  std::remove(path.c_str());
}
