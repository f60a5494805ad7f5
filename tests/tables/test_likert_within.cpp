// The questionnaire compared within participants (each answered after each condition) against R:
// every number of tests/golden/likert/likert_within_golden.csv (made by likert_within_golden.R with
// wilcox.test(x, y, paired = TRUE), effectsize::rank_biserial(paired = TRUE), t.test(paired = TRUE),
// BayesFactor::ttestBF(paired = TRUE), friedman.test, effectsize::kendalls_w, p.adjust "holm",
// binom.test and mcnemar.test) on tests/data/likert/within_{two,three,yesno}.csv and on the ten data
// sets the script generates into tests/golden/likert/data/within_*.csv (two conditions: complete,
// missing answers and absent participants, ties, small, large; three to five conditions), then who
// is left out and the protection of the pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/tables/likert.hpp"
#include "feint/tables/likert_conditions.hpp"
#include "feint/tables/yes_no.hpp"

using namespace feint;

namespace {

// data, item, group1, group2, quantity
using Key = std::tuple<std::string, std::string, std::string, std::string, std::string>;

std::map<Key, double> read_golden() {
  std::ifstream in(std::string(FEINT_SOURCE_DIR) + "/tests/golden/likert/likert_within_golden.csv");
  std::map<Key, double> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[{f.at(0), f.at(1), f.at(2), f.at(3), f.at(4)}] = std::stod(f.at(5));
  }
  return out;
}

io::Questionnaire load(const std::string& name) {
  return io::load_questionnaire(std::string(FEINT_TEST_DATA_DIR) + "/likert/" + name, {});
}

// A generated data set of likert_within_golden.R.
io::Questionnaire load_generated(const std::string& data) {
  return io::load_questionnaire(std::string(FEINT_SOURCE_DIR) + "/tests/golden/likert/data/within_" + data + ".csv",
                                {});
}

tables::LikertAnalysis paired_two(const io::Questionnaire& q) {
  tables::LikertSettings s;
  s.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  s.paired = true;
  return tables::analyze_likert(q, s);
}
tables::LikertAnalysis paired_two() { return paired_two(load("within_two.csv")); }

tables::LikertConditions within_three(const io::Questionnaire& q) {
  tables::LikertSettings s;
  s.paired = true;
  return tables::analyze_likert_conditions(q, s);
}
tables::LikertConditions within_three() { return within_three(load("within_three.csv")); }

struct Checker {
  std::map<Key, double> golden = read_golden();
  std::size_t checked = 0;
  void operator()(const Key& key, std::optional<double> value, double tolerance = 1e-10) {
    const std::string what = std::get<0>(key) + " " + std::get<1>(key) + " " + std::get<2>(key) + " " +
                             std::get<3>(key) + " " + std::get<4>(key);
    const auto it = golden.find(key);
    ASSERT_NE(it, golden.end()) << what;
    ASSERT_TRUE(value.has_value()) << what;
    EXPECT_NEAR(*value, it->second, tolerance * std::max(1.0, std::abs(it->second))) << what;
    ++checked;
  }
  // The rows of one paired comparison: signed-rank, then paired t.
  void pair(const std::string& data, const tables::TidyRow& w, const tables::TidyRow& t, bool holm) {
    const auto& g1 = w.group1;
    const auto& g2 = w.group2;
    ASSERT_EQ(w.result.test, "wilcoxon_signed_rank");
    ASSERT_EQ(t.result.test, "paired_t");
    (*this)({data, w.metric, g1, g2, "V"}, w.result.statistic);
    (*this)({data, w.metric, g1, g2, "p_w"}, w.result.p_value);
    (*this)({data, w.metric, g1, g2, "r_rb"}, w.result.rank_biserial);
    (*this)({data, t.metric, g1, g2, "t"}, t.result.statistic);
    (*this)({data, t.metric, g1, g2, "df_t"}, t.result.df);
    (*this)({data, t.metric, g1, g2, "p_t"}, t.result.p_value);
    (*this)({data, t.metric, g1, g2, "d_z"}, t.result.cohen_d);
    (*this)({data, t.metric, g1, g2, "bf10"}, t.result.bf10, 1e-6);  // BayesFactor integrates numerically
    if (holm) {
      (*this)({data, w.metric, g1, g2, "p_w_holm"}, w.result.p_adjusted);
      (*this)({data, t.metric, g1, g2, "p_t_holm"}, t.result.p_adjusted);
    }
  }
};

}  // namespace

TEST(LikertWithin, TwoConditionsPairedEqualR) {
  Checker check;
  const auto a = paired_two();
  ASSERT_TRUE(a.paired);
  ASSERT_EQ(a.rows.size(), 8u);
  for (std::size_t i = 0; i < a.rows.size(); i += 2) check.pair("two", a.rows[i], a.rows[i + 1], false);
  EXPECT_EQ(check.checked, 32u);
}

TEST(LikertWithin, ParticipantsInOneConditionAreLeftOutAndNamed) {
  const auto a = paired_two();
  EXPECT_EQ(a.unpaired, (std::vector<std::string>{"P16", "P15"}));
  const bool named = std::any_of(a.notes.begin(), a.notes.end(), [](const std::string& n) {
    return n.find("Left out: 2 participants") != std::string::npos && n.find("P16, P15") != std::string::npos;
  });
  EXPECT_TRUE(named);
  // 14 complete pairs; P05 has no random entertainment answer: 13 pairs for that item.
  EXPECT_EQ(a.rows[0].result.n1, 13u);
  EXPECT_EQ(a.rows[2].result.n1, 14u);
  // Between participants the same file is refused: Mann-Whitney needs independent groups.
  tables::LikertSettings s;
  s.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  EXPECT_THROW(tables::analyze_likert(load("within_two.csv"), s), InvalidData);
}

// Friedman's test with Kendall's W per item, then every pair (Holm): the checks of one data set.
void check_across(Checker& check, const std::string& data, const tables::LikertConditions& a) {
  ASSERT_TRUE(a.paired);
  ASSERT_EQ(a.omnibus.size(), 4u);
  ASSERT_EQ(a.kendalls_w.size(), 4u);
  for (std::size_t k = 0; k < a.omnibus.size(); ++k) {
    const auto& row = a.omnibus[k];
    ASSERT_EQ(row.result.test, "friedman");
    check({data, row.metric, row.group1, "", "chi2"}, row.result.statistic);
    check({data, row.metric, row.group1, "", "df"}, row.result.df);
    check({data, row.metric, row.group1, "", "p"}, row.result.p_value);
    check({data, row.metric, row.group1, "", "n"}, static_cast<double>(row.result.n1));
    check({data, row.metric, row.group1, "", "W"}, a.kendalls_w[k]);
  }
  for (const auto& pair : a.pairs)
    for (std::size_t i = 0; i < pair.rows.size(); i += 2) check.pair(data, pair.rows[i], pair.rows[i + 1], true);
}

TEST(LikertWithin, ThreeConditionsFriedmanKendallAndHolmPairsEqualR) {
  Checker check;
  const auto a = within_three();
  ASSERT_EQ(a.pairs.size(), 3u);
  check_across(check, "three", a);
  EXPECT_EQ(check.checked, 4u * 5u + 3u * 4u * 10u);
}

TEST(LikertWithin, GeneratedDataSetsEqualRInEveryNumber) {
  Checker check;
  std::map<std::string, std::size_t> expected;  // golden values per generated data set
  for (const auto& [key, _] : check.golden)
    if (const auto& d = std::get<0>(key); d != "two" && d != "three" && d != "yesno") ++expected[d];
  ASSERT_EQ(expected.size(), 10u) << "golden file missing or truncated";
  for (const auto& [data, n] : expected) {
    const std::size_t before = check.checked;
    const io::Questionnaire q = load_generated(data);
    if (data.rfind("two_", 0) == 0) {
      const auto a = paired_two(q);
      for (std::size_t i = 0; i < a.rows.size(); i += 2) check.pair(data, a.rows[i], a.rows[i + 1], false);
    } else {
      const auto a = within_three(q);
      EXPECT_GE(a.conditions.size(), 3u) << data;
      check_across(check, data, a);
    }
    EXPECT_EQ(check.checked - before, n) << data;
  }
}

TEST(LikertWithin, PairsAreProtectedByTheFriedmanTest) {
  const auto a = within_three();
  for (std::size_t k = 0; k < a.omnibus.size(); ++k) {
    const bool omnibus = *a.omnibus[k].result.p_value < 0.05;
    for (const auto& pair : a.pairs) {
      const auto& w = pair.rows[2 * k];
      const bool claims = w.label != "n.s." && w.label != "not computable";
      if (claims) {
        EXPECT_TRUE(omnibus) << w.metric;
        EXPECT_LT(*w.result.p_adjusted, 0.05) << w.metric;
      }
      if (omnibus && *w.result.p_adjusted < 0.05) {
        EXPECT_TRUE(claims) << w.metric << " " << w.group1 << w.group2;
      }
    }
  }
  // deception differs (Friedman p = 0.00066): its adaptive-fixed-block pair is labelled.
  EXPECT_LT(*a.omnibus[1].result.p_value, 0.001);
  EXPECT_EQ(a.pairs[1].rows[2].label, "A>B");
}

TEST(YesNoWithin, McNemarExactAndChiSquareEqualR) {
  Checker check;
  tables::YesNoSettings s;
  s.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  s.paired = true;
  const auto a = tables::analyze_yes_no_file(std::string(FEINT_TEST_DATA_DIR) + "/likert/within_yesno.csv", s);
  ASSERT_EQ(a.rows.size(), 4u);
  for (std::size_t i = 0; i < a.rows.size(); i += 2) {
    const auto& e = a.rows[i].result;
    const auto& c = a.rows[i + 1].result;
    const std::string q = a.rows[i].metric;
    ASSERT_EQ(e.test, "mcnemar_exact");
    ASSERT_EQ(c.test, "mcnemar");
    check({"yesno", q, "adaptive", "random", "pairs"}, static_cast<double>(e.n1));
    check({"yesno", q, "adaptive", "random", "b"}, e.statistic);
    check({"yesno", q, "adaptive", "random", "p_exact"}, e.p_value);
    check({"yesno", q, "adaptive", "random", "or"}, e.estimate);
    check({"yesno", q, "adaptive", "random", "or_low"}, e.conf_low);
    check({"yesno", q, "adaptive", "random", "or_high"}, e.conf_high);
    check({"yesno", q, "adaptive", "random", "chi2"}, c.statistic);
    check({"yesno", q, "adaptive", "random", "p_chi2"}, c.p_value);
    check({"yesno", q, "adaptive", "random", "p_a"}, e.mean1);
    check({"yesno", q, "adaptive", "random", "p_b"}, e.mean2);
  }
  EXPECT_EQ(check.checked, 20u);
  EXPECT_NE(a.notes.back().find("Left out: 1 participant answered in only one of the two conditions (P22)"),
            std::string::npos);
  // Between participants the same answers are refused (Fisher's test needs independent groups).
  s.paired = false;
  EXPECT_THROW(tables::analyze_yes_no_file(std::string(FEINT_TEST_DATA_DIR) + "/likert/within_yesno.csv", s),
               InvalidData);
}
