// Table 1's "≈" (docs/tables.md "Labels"): one meaning in every command and format, "≈" only from
// BF01 >= 3 or TOST within the margin; a non-significant p alone is "n.s.".
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "feint/tables/table1.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/bayes_factor.hpp"

using namespace feint;
using namespace feint::tables;

namespace {

// One condition, one iteration, n participants: error values around `mean` with sd 0.1.
io::ScoresTable table_of(std::size_t n, double mean, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> d(mean, 0.1);
  io::ScoresTable t;
  t.metrics = {"error"};
  t.has_condition = true;
  for (std::size_t i = 0; i < n; ++i) t.records.push_back({"P" + std::to_string(i), "adaptive", 1, {d(rng)}, 0});
  return t;
}

const TidyRow& difference_row(const Table1& t) { return t.rows[t.blocks.at(0).cells.at(0).at(0).difference_row]; }

}  // namespace

TEST(Table1Equivalence, ApproxNeedsBf01OrTostEverywhere) {
  Table1Options o;
  o.metrics = {{"error", 0.5}};
  // Small n, a mean off the reference by a little: not significant, BF01 below 3.
  const io::ScoresTable small = table_of(6, 0.53, 1);
  const Table1 table = build_table1(small, o);
  const TidyRow& s = difference_row(table);
  ASSERT_TRUE(s.result.p_value && s.result.log_bf10);
  ASSERT_GE(*s.result.p_value, 0.05);
  ASSERT_LT(-*s.result.log_bf10, std::log(3.0));
  EXPECT_EQ(s.label, "n.s.");

  // Large n at the reference: BF01 >= 3 earns "≈".
  const io::ScoresTable large = table_of(400, 0.5, 2);
  const Table1 big = build_table1(large, o);
  const TidyRow& b = difference_row(big);
  ASSERT_TRUE(b.result.log_bf10);
  ASSERT_GE(*b.result.p_value, 0.05);
  EXPECT_GE(-*b.result.log_bf10, std::log(3.0)) << "BF01 is large at n = 400 under the null";
  EXPECT_EQ(b.label, "M\u2248R");

  // TOST within a wide margin earns "≈" even when BF01 < 3.
  o.equivalence = 0.2;
  const Table1 tost = build_table1(small, o);
  EXPECT_EQ(difference_row(tost).label, "M\u2248R");
  o.equivalence = 0.001;  // far too narrow: not shown equivalent
  EXPECT_EQ(difference_row(build_table1(small, o)).label, "n.s.");

  // The note says where "≈" comes from, in every format.
  for (auto format : {OutputFormat::markdown, OutputFormat::text, OutputFormat::latex}) {
    std::string out;
    for (char c : render_table1(table, format)) {  // notes wrap: compare words, not lines
      if (c == '\n') c = ' ';
      if (c != ' ' || out.empty() || out.back() != ' ') out += c;
    }
    EXPECT_NE(out.find("evidence for no difference, from the JZS Bayes factor BF01"), std::string::npos) << out;
    EXPECT_NE(out.find("n.s.: not significant and not shown to be equivalent"), std::string::npos) << out;
  }
}
