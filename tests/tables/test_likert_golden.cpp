// `feint likert` assembly against R: every per-item number of tests/golden/likert/golden.csv
// (made by tests/golden/likert/make_golden.R with R 4.2 and psych) must come out of
// analyze_likert_file on each of its six data sets: tests/data/likert/golden_input.csv and the five
// the script generates into tests/golden/likert/data/ (unbalanced, missing answers, ties, small,
// large). The rank and t tests themselves have
// their own golden tests (tests/stats); this checks that the right data reach the right test with
// the right settings, and that descriptives, counts, p-adjustment and alpha are assembled right.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "feint/tables/likert.hpp"
#include "accuracy.hpp"

using feint::tables::analyze_likert_file;
using feint::tables::LikertAnalysis;
using feint::tables::LikertSettings;
using feint::tables::TidyRow;

namespace {

struct Golden {
  std::string data, run, group, name, quantity;
  double value = 0.0;
};

std::vector<Golden> read_golden() {
  std::ifstream in(std::string(FEINT_SOURCE_DIR) + "/tests/golden/likert/golden.csv");
  std::vector<Golden> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    Golden g;
    std::string value;
    std::getline(ss, g.data, ',');
    std::getline(ss, g.run, ',');
    std::getline(ss, g.group, ',');
    std::getline(ss, g.name, ',');
    std::getline(ss, g.quantity, ',');
    std::getline(ss, value, ',');
    g.value = std::stod(value);
    out.push_back(g);
  }
  return out;
}

std::string input() { return std::string(FEINT_TEST_DATA_DIR) + "/likert/golden_input.csv"; }

// The file of a data set of golden.csv.
std::string input(const std::string& data) {
  return data == "input" ? input() : std::string(FEINT_SOURCE_DIR) + "/tests/golden/likert/data/" + data + ".csv";
}

LikertSettings common() {
  LikertSettings s;
  s.load.reverse = {"boring"};
  s.composites = {feint::tables::parse_composite("enjoyment=entertainment,boring,fun")};
  // golden.csv's alpha is psych::alpha(na.omit(...)); the pairwise default is checked against
  // psych in test_likert_alpha.cpp.
  s.alpha_missing = feint::stats::AlphaMissing::complete_cases;
  return s;
}

const TidyRow* find_row(const LikertAnalysis& a, const std::string& name, const std::string& group,
                        const std::string& test) {
  for (const auto& r : a.rows) {
    if (r.metric == name && r.group1 == group && r.result.test == test) return &r;
  }
  return nullptr;
}

const feint::tables::LikertSummary* find_summary(const LikertAnalysis& a, const std::string& name,
                                                 const std::string& group) {
  for (const auto& s : a.summaries) {
    if (s.name == name && s.group == group) return &s;
  }
  return nullptr;
}

/// The value feint computed for a golden quantity; nullopt when it has none (a failure).
std::optional<double> feint_value(const LikertAnalysis& a, const Golden& g,
                                  const std::string& group, const std::string& rank_test,
                                  const std::string& t_test) {
  const auto* s = find_summary(a, g.name, group);
  const auto* rank = find_row(a, g.name, group, rank_test);
  const auto* t = find_row(a, g.name, group, t_test);
  if (s == nullptr || rank == nullptr || t == nullptr) return std::nullopt;
  const std::string& q = g.quantity;
  if (q == "n") return static_cast<double>(s->n);
  if (q == "missing") return static_cast<double>(s->missing);
  if (q == "mean") return s->mean;
  if (q == "sd") return s->sd;
  if (q == "q1") return s->q1;
  if (q == "median") return s->median;
  if (q == "q3") return s->q3;
  if (q == "iqr") return s->iqr;
  if (q == "pct_below") return s->pct_below;
  if (q == "pct_at") return s->pct_at;
  if (q == "pct_above") return s->pct_above;
  if (q.rfind("count_", 0) == 0) {
    const auto k = static_cast<std::size_t>(std::stoi(q.substr(6)) - 1);
    if (k >= s->counts.size()) return std::nullopt;
    return static_cast<double>(s->counts[k]);
  }
  if (q == "V" || q == "W") return rank->result.statistic;
  if (q == "wilcoxon_p" || q == "mw_p") return rank->result.p_value;
  if (q == "wilcoxon_exact") {
    if (!rank->result.exact) return std::nullopt;
    return *rank->result.exact ? 1.0 : 0.0;
  }
  if (q == "rank_biserial") return rank->result.rank_biserial;
  if (q == "wilcoxon_p_holm") return rank->result.p_adjusted;
  if (q == "t") return t->result.statistic;
  if (q == "t_df") return t->result.df;
  if (q == "t_p") return t->result.p_value;
  if (q == "t_p_holm") return t->result.p_adjusted;
  if (q == "cohen_d") return t->result.cohen_d;
  if (q == "median_B") return rank->result.median2;
  if (q == "iqr_B") return rank->result.iqr2;
  // Composite reliability.
  for (const auto& rel : a.reliability) {
    const std::string want = rank_test == "mann_whitney" ? "adaptive+random" : group;
    if (rel.name != g.name || rel.group != want) continue;
    if (q == "alpha_n") return static_cast<double>(rel.n);
    if (q == "cronbach_alpha") {
      EXPECT_EQ(rank->cronbach_alpha, rel.alpha);  // the table column carries the same alpha
      return rel.alpha;
    }
    for (std::size_t j = 0; j < rel.items.size(); ++j) {
      if (q == "alpha_if_dropped_" + rel.items[j] && j < rel.if_dropped.size()) {
        return rel.if_dropped[j];
      }
    }
  }
  return std::nullopt;
}

bool close(double got, double want) {
  const double diff = std::fabs(got - want);
  feint::test::record("Likert tables (psych, wilcox.test)", got, want);
  return diff <= 1e-10 * std::fabs(want) || diff <= 1e-13;
}

// One data set: the three runs of make_golden.R, every golden number of `data` compared.
std::size_t check_data_set(const std::vector<Golden>& golden, const std::string& data) {
  LikertSettings one = common();
  one.p_adjust = feint::stats::PAdjustMethod::holm;
  const auto a_one = analyze_likert_file(input(data), one);
  EXPECT_DOUBLE_EQ(a_one.reference, 4.0);  // the midpoint of 1-7

  LikertSettings cmp = common();
  cmp.compare = std::make_pair(std::string("adaptive"), std::string("random"));
  const auto a_cmp = analyze_likert_file(input(data), cmp);

  LikertSettings paper;
  paper.paper = true;
  paper.condition = "adaptive";
  const auto a_paper = analyze_likert_file(input(data), paper);
  EXPECT_DOUBLE_EQ(a_paper.reference, 3.5);
  EXPECT_EQ(a_paper.names,
            (std::vector<std::string>{"entertainment", "deception", "intelligence", "trust"}));

  std::size_t checked = 0;
  for (const auto& g : golden) {
    if (g.data != data) continue;
    std::optional<double> got;
    if (g.run == "one") {
      got = feint_value(a_one, g, g.group, "wilcoxon_signed_rank", "one_sample_t");
    } else if (g.run == "compare") {
      // Two-sample rows are keyed by group 1 (A); B's median/IQR are median2/iqr2.
      got = feint_value(a_cmp, g, "adaptive", "mann_whitney", "welch_t");
    } else if (g.run == "paper") {
      got = feint_value(a_paper, g, g.group, "wilcoxon_signed_rank", "one_sample_t");
    }
    const std::string what = g.data + "/" + g.run + "/" + g.group + "/" + g.name + "/" + g.quantity;
    if (!got.has_value()) {
      ADD_FAILURE() << what << ": feint has no value";
      continue;
    }
    EXPECT_TRUE(close(*got, g.value)) << what << ": feint " << *got << ", R " << g.value;
    ++checked;
  }
  return checked;
}

}  // namespace

TEST(LikertGolden, EveryNumberOfEveryDataSetMatchesR) {
  const auto golden = read_golden();
  std::set<std::string> sets;
  for (const auto& g : golden) sets.insert(g.data);
  ASSERT_EQ(sets, (std::set<std::string>{"input", "balanced", "unbalanced_missing", "ties", "large", "small"}))
      << "golden file missing or truncated";
  std::size_t checked = 0;
  for (const auto& data : sets) {
    const std::size_t n = check_data_set(golden, data);
    EXPECT_GT(n, 400u) << data;
    checked += n;
  }
  EXPECT_EQ(checked, golden.size());
}

TEST(LikertGolden, AllAnswersAtTheReferenceAreNotComputable) {
  LikertSettings one = common();
  one.p_adjust = feint::stats::PAdjustMethod::holm;
  const auto a = analyze_likert_file(input(), one);
  const auto* w = find_row(a, "trust", "pilot", "wilcoxon_signed_rank");
  const auto* t = find_row(a, "trust", "pilot", "one_sample_t");
  ASSERT_NE(w, nullptr);
  ASSERT_NE(t, nullptr);
  EXPECT_FALSE(w->result.computed);
  EXPECT_FALSE(t->result.computed);
  EXPECT_FALSE(w->result.p_adjusted.has_value());
  EXPECT_EQ(w->label, "not computable");
  EXPECT_EQ(t->label, "not computable");
  bool noted = false;
  for (const auto& n : a.notes) noted = noted || n.rfind("Not computable: trust in pilot", 0) == 0;
  EXPECT_TRUE(noted);
  // The summary of that item is still there: three answers, all 4.
  const auto* s = find_summary(a, "trust", "pilot");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->n, 3u);
  EXPECT_EQ(s->pct_at, 100.0);
}
