// End-to-end tests of `feint describe` (runs FEINT_EXE), checked against R
// (tests/data/table/golden_describe.csv, made by tests/data/table/make_golden.R).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {
const std::string kTableDir = std::string(FEINT_TEST_DATA_DIR) + "/table";
const std::string kSmall = kTableDir + "/scores_small.csv";
}  // namespace

TEST(DescribeCli, ByGroupMatchesR) {
  TempDir dir;
  const auto out = (dir / "d.csv").string();
  const auto r = run_feint("describe " + shell_quote(kSmall) +
                           " --column error --by condition --format csv -o " + shell_quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  feint::io::CsvReader got(out);
  feint::io::CsvReader want(kTableDir + "/golden_describe.csv");
  EXPECT_EQ(got.header(), (std::vector<std::string>{"variable", "group", "n", "mean", "sd", "se",
                                                    "min", "q1", "median", "q3", "max",
                                                    "conf_low", "conf_high", "autocorr_lag1"}));
  int rows = 0;
  while (want.next()) {
    ASSERT_TRUE(got.next());
    EXPECT_EQ(got.field(0), "error");
    EXPECT_EQ(got.field(1), want.field(0));
    EXPECT_EQ(got.field(2), want.field(1));  // n
    for (std::size_t i = 3; i < 14; ++i) {
      const double g = *feint::io::parse_double(got.field(i));
      const double w = *feint::io::parse_double(want.field(i - 1));
      EXPECT_NEAR(g, w, 1e-12 * std::fabs(w)) << got.header()[i] << " " << want.field(0);
    }
    ++rows;
  }
  EXPECT_EQ(rows, 2);
  EXPECT_FALSE(got.next());
}

TEST(DescribeCli, NumbersRoundTripAndTextHasANote) {
  TempDir dir;
  const auto in = dir / "x.csv";
  write_text(in, "x\n0.1\n0.2\n\n0.30000000000000004\n");
  auto r = run_feint("describe " + shell_quote(in.string()) + " --column x --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"group\": null, \"n\": 3,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"max\": 0.30000000000000004"), std::string::npos) << r.out;
  write_text(in, "x,y\n0.1,1\n,2\n0.2,3\n");
  r = run_feint("describe " + shell_quote(in.string()) + " --column X");  // case-insensitive
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Descriptive statistics of x"), std::string::npos);
  EXPECT_NE(r.out.find("x: 1 empty cell excluded as missing."), std::string::npos) << r.out;
}

TEST(DescribeCli, NotComputableValuesAreEmptyAndExplained) {
  TempDir dir;
  const auto in = dir / "x.csv";
  write_text(in, "g,x\na,1\nb,2\nb,2\n");
  const auto r = run_feint("describe " + shell_quote(in.string()) + " --column x --by g --format markdown");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| x | a | 1 | 1 |  |  | 1 | 1 | 1 | 1 | 1 |  |  |  |"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("g = a: n < 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("g = b: constant data"), std::string::npos) << r.out;
}

TEST(DescribeCli, ErrorsAndExitCodes) {
  TempDir dir;
  const auto in = dir / "x.csv";
  write_text(in, "g,x\na,1\nb,oops\n");
  auto r = run_feint("describe " + shell_quote(in.string()) + " --column x --by g");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_EQ(r.err, "feint: error: " + in.string() +
                       ":3: column 'x': 'oops' is not a number (g b; expected a finite number "
                       "with a decimal point, or an empty cell)\n");
  r = run_feint("describe " + shell_quote(in.string()) + " --column y");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find(":1: column 'y' (--column) is missing; the header has: g, x"), std::string::npos);
  write_text(in, "g,x\n");
  EXPECT_EQ(run_feint("describe " + shell_quote(in.string()) + " --column x").exit_code, 65);
  EXPECT_EQ(run_feint("describe " + shell_quote(kSmall)).exit_code, 64);  // --column required
  EXPECT_EQ(run_feint("describe " + shell_quote(kSmall) + " --column error --format xml").exit_code, 64);
  EXPECT_EQ(run_feint("describe " + shell_quote(kSmall) + " --column error --conf-level 2").exit_code, 64);
  EXPECT_EQ(run_feint("describe /nonexistent.csv --column x").exit_code, 74);
}
