// The yes/no questions compared between conditions against R, on the 21 generated data sets of
// tests/golden/yesno/data (made by tests/golden/yesno/yesno_conditions_golden.R with fisher.test,
// chisq.test, effectsize::cramers_v, prop.test, binom.test, mcnemar.test, friedman.test and
// p.adjust "holm"): two conditions and three to five, between and within participants, balanced
// and unbalanced, with missing answers, a condition without answers and conditions answering alike.
// Every number R gives must come out of analyze_yes_no_file, and every number feint gives must
// have R's beside it (a test one computes and the other cannot is a failure). Then the protection
// of the pairs by the omnibus test and what the tables say.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "feint/io/csv.hpp"
#include "feint/stats/contingency.hpp"
#include "feint/tables/yes_no.hpp"
#include "accuracy.hpp"

using namespace feint;

namespace {

// data, question, group1, group2, quantity
using Key = std::tuple<std::string, std::string, std::string, std::string, std::string>;

std::string golden_dir() { return std::string(FEINT_SOURCE_DIR) + "/tests/golden/yesno"; }

std::map<Key, double> read_golden() {
  std::ifstream in(golden_dir() + "/yesno_conditions_golden.csv");
  std::map<Key, double> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = io::split_csv_line(line);
    out[{f.at(0), f.at(1), f.at(2), f.at(3), f.at(4)}] = std::stod(f.at(5));
  }
  return out;
}

// The settings of a data set: b* between, w* within; two conditions compared as a pair, more
// across the conditions.
tables::YesNoAnalysis analyse(const std::string& data) {
  tables::YesNoSettings s;
  s.paired = data[0] == 'w';
  if (data[1] == '2') s.compare = std::pair<std::string, std::string>{"adaptive", "random"};
  return tables::analyze_yes_no_file(golden_dir() + "/data/" + data + ".csv", s);
}

// Whether feint's value agrees with R's: 1e-10 relative, except where R (or the quantity) is less
// precise. R's fisher.test solves the odds ratio and its interval with uniroot at tol 1.2e-4 on psi
// or on 1 / psi (docs/yes-no.md; as tests/stats/test_proportions.cpp); effectsize's Cramér's V
// bound comes from optim at abstol 1e-9 (about 1e-6 on V). V = sqrt(phi^2 - (C - 1)/(N - 1)) is
// sqrt of a difference that can vanish: it is compared as V^2, the quantity both compute to
// double precision (a bias-corrected V of 3e-9 is R's 0).
bool agrees(const std::string& quantity, double got, double want) {
  const double d = std::fabs(got - want);
  if (quantity == "or" || quantity == "or_low" || quantity == "or_high")
    return want == 0 ? got == 0 : d <= 2e-4 * std::max(1.0, want * want);
  if (quantity == "V_low" || quantity == "V_unadjusted_low") return d <= 1e-5;
  if (quantity.rfind("V", 0) == 0) return std::fabs(got * got - want * want) <= 1e-10 * want * want + 1e-15;
  return d <= 1e-10 * std::fabs(want) || d <= 1e-14;
}

/// feint's numbers of one data set under R's names.
struct Values {
  std::string data;
  std::map<Key, double> got;
  void put(const std::string& q, const std::string& g1, const std::string& g2, const std::string& what,
           std::optional<double> v) {
    if (v && std::isfinite(*v)) got[{data, q, g1, g2, what}] = *v;
  }
};

void pair_values(Values& v, const tables::TidyRow& row) {
  const auto& r = row.result;
  if (!r.computed) return;
  auto put = [&](const char* what, std::optional<double> x) { v.put(row.metric, row.group1, row.group2, what, x); };
  // Fisher's odds ratio at the lower end of the support is 0 in both, but R also says 0 where the
  // margins allow one table only (feint: none); the golden leaves R's 0 out.
  const bool or_positive = r.estimate && *r.estimate > 0;
  if (r.test == "fisher_exact") {
    put("fisher_p", r.p_value);
    put("fisher_p_holm", r.p_adjusted);
    put("or", or_positive ? r.estimate : std::nullopt);
    put("or_low", r.conf_low);
    put("or_high", r.conf_high);
  } else if (r.test == "prop_test") {
    put("x2_yates", r.statistic);
    put("prop_p", r.p_value);
    put("prop_p_holm", r.p_adjusted);
    put("diff_low", r.conf_low);
    put("diff_high", r.conf_high);
  } else if (r.test == "mcnemar_exact") {
    const double n = static_cast<double>(r.n1);
    put("pairs", n);
    put("b", r.statistic);
    put("c", std::round(*r.statistic - n * (*r.mean1 - *r.mean2)));  // mean1 - mean2 = (b - c) / n
    put("p_exact", r.p_value);
    put("p_exact_holm", r.p_adjusted);
    put("or", r.estimate);  // b / c: 0 when b = 0, as R's
    put("or_low", r.conf_low);
    put("or_high", r.conf_high);
    put("p_a", r.mean1);
    put("p_b", r.mean2);
  } else if (r.test == "mcnemar") {
    put("chi2", r.statistic);
    put("p_chi2", r.p_value);
    put("p_chi2_holm", r.p_adjusted);
  }
}

void omnibus_values(Values& v, const tables::TidyRow& row) {
  const auto& r = row.result;
  if (!r.computed) return;
  auto put = [&](const char* what, std::optional<double> x) { v.put(row.metric, row.group1, "", what, x); };
  if (r.test == "fisher_exact_conditions") {
    put("fisher_p", r.p_value);
  } else if (r.test == "chisq_test") {
    put("n", static_cast<double>(r.n1));
    put("chi2", r.statistic);
    put("df", r.df);
    put("chi2_p", r.p_value);
    put("V", r.estimate);
    put("V_low", r.conf_low);
    put("V_low_exact", r.conf_low);
    // The unadjusted V of the same table (the tables report effectsize's default, adjusted).
    const auto u = stats::cramers_v(*r.statistic, r.n1, static_cast<std::size_t>(*r.df) + 1, 2, false);
    put("V_unadjusted", u.estimate);
    put("V_unadjusted_low", u.low);
    put("V_unadjusted_low_exact", u.low);
  } else if (r.test == "cochran_q") {
    put("n", static_cast<double>(r.n1));
    put("Q", r.statistic);
    put("df", r.df);
    put("p", r.p_value);
  }
}

Values values_of(const std::string& data) {
  const auto a = analyse(data);
  Values v{data, {}};
  for (const auto& s : a.summaries) {
    const auto& p = s.proportion;
    v.put(s.question, s.group, "", "yes", static_cast<double>(p.x));
    v.put(s.question, s.group, "", "n", static_cast<double>(p.n));
    if (p.n == 0) continue;
    v.put(s.question, s.group, "", "exact_low", p.exact_low);
    v.put(s.question, s.group, "", "exact_high", p.exact_high);
    v.put(s.question, s.group, "", "wilson_low", p.wilson_low);
    v.put(s.question, s.group, "", "wilson_high", p.wilson_high);
  }
  for (const auto& row : a.omnibus) omnibus_values(v, row);
  for (const auto& row : a.rows) pair_values(v, row);
  return v;
}

}  // namespace

TEST(YesNoConditionsGolden, EveryNumberOfEveryDataSetEqualsR) {
  const auto golden = read_golden();
  std::set<std::string> sets;
  for (const auto& [k, _] : golden) sets.insert(std::get<0>(k));
  ASSERT_EQ(sets.size(), 21u) << "golden file missing or truncated";
  std::size_t checked = 0;
  for (const auto& data : sets) {
    const Values v = values_of(data);
    for (const auto& [key, want] : golden) {
      if (std::get<0>(key) != data) continue;
      const std::string what = data + " " + std::get<1>(key) + " " + std::get<2>(key) + " " + std::get<3>(key) +
                               " " + std::get<4>(key);
      const auto it = v.got.find(key);
      if (it == v.got.end()) {
        ADD_FAILURE() << "feint has no value for " << what;
        continue;
      }
      const double got = it->second;
      const std::string& quantity = std::get<4>(key);
      if (quantity.rfind("or", 0) != 0 && quantity.rfind("V", 0) != 0)
        test::record("yes/no between and within conditions (fisher.test, chisq.test, friedman.test)", got, want,
                     what);
      EXPECT_TRUE(agrees(quantity, got, want)) << what << ": feint " << got << ", R " << want;
      ++checked;
    }
    for (const auto& [key, got] : v.got)
      EXPECT_TRUE(golden.count(key)) << "R has no value for " << data << " " << std::get<1>(key) << " "
                                     << std::get<2>(key) << " " << std::get<3>(key) << " " << std::get<4>(key)
                                     << " (feint " << got << ")";
  }
  EXPECT_EQ(checked, golden.size());
}
