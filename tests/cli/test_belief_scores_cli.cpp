// End-to-end: the belief-trace columns of `feint score` (docs/metrics.md) are metric columns like
// any other for `feint table` and `feint describe`; an undefined final_belief_time is an empty
// cell (a missing value, counted), never 0.
#include <gtest/gtest.h>

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

// 11 samples at t = 0..10: toward the false (left) side by `away`, then right to `end`.
std::string trial(const std::string& participant, int iteration, double away, double end) {
  std::string s;
  const std::vector<double> shape = {0.5, 0.5 - away / 2, 0.5 - away, 0.5 - away, 0.5 - away / 2,
                                     0.5, 0.6, 0.7, 0.8, 0.9, end};
  for (int i = 0; i <= 10; ++i) {
    s += participant + ",adaptive," + std::to_string(iteration) + ",exaggerating,main,right," +
         std::to_string(i) + "," + feint::io::format_double(shape[static_cast<std::size_t>(i)]) +
         ",0.25\n";
  }
  return s;
}

}  // namespace

TEST(BeliefScoresCli, NewColumnsTabulateAndAnUndefinedFinalBeliefIsMissing) {
  TempDir d;
  std::string log = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  const std::vector<double> away = {0.12, 0.3, 0.2, 0.4};  // all moves beyond the 0.05 dead band
  for (int p = 0; p < 4; ++p) {
    for (int it = 1; it <= 2; ++it) {
      // P04 ends its first trial back in the middle: it never settles on the true side.
      const double end = (p == 3 && it == 1) ? 0.5 : 1.0;
      log += trial("P0" + std::to_string(p + 1), it, away[static_cast<std::size_t>(p)] / it, end);
    }
  }
  write_text(d / "log.csv", log);
  const std::string scores = shell_quote((d / "scores.csv").string());
  const auto scored = run_feint("score " + shell_quote((d / "log.csv").string()) + " -o " + scores);
  ASSERT_EQ(scored.exit_code, 0) << scored.err;

  feint::io::CsvReader in((d / "scores.csv").string());
  const auto col = [&](const char* name) {
    const int c = in.column(name);
    EXPECT_GE(c, 0) << name;
    return static_cast<std::size_t>(c);
  };
  const auto fb = col("final_belief_time"), flips = col("flips"), p = col("participant"),
             it = col("iteration"), td = col("time_deceived");
  int empty = 0;
  while (in.next()) {
    const bool never = in.field(p) == "P04" && in.field(it) == "1";
    if (never) {
      EXPECT_EQ(in.field(fb), "");  // undefined: empty, not 0
      ++empty;
    } else {
      // 0.5 at t = 5 to 0.6 at t = 6: beyond 0.55 from t = 5.5 on.
      EXPECT_NEAR(*feint::io::parse_double(in.field(fb)), 5.5, 1e-12);
    }
    EXPECT_EQ(in.field(flips), never ? "2" : "1");  // away and back (and away again)
    EXPECT_FALSE(in.field(td).empty());
  }
  EXPECT_EQ(empty, 1);

  const auto r = run_feint("table " + scores +
                           " --metric final_belief_time=5 --metric time_deceived=0.2 "
                           "--metric flips=0 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Iteration 1: three participants have a final belief (5.5 each), one is missing.
  EXPECT_NE(r.out.find("\nfinal_belief_time,1,one_sample_t,One Sample t-test,two.sided,5,adaptive,,3,"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\ntime_deceived,2,one_sample_t,"), std::string::npos) << r.out;
  const auto desc = run_feint("describe " + scores + " --column final_belief_time");
  EXPECT_EQ(desc.exit_code, 0) << desc.err << desc.out;
}

TEST(BeliefScoresCli, ShortZeroDurationAndStillTrialsNeverGiveASilentNumber) {
  TempDir d;
  const std::string log =
      "participant,iteration,target,t,pad\n"
      "P1,1,right,0,0.5\n"                                      // one sample: rejected
      "P1,2,right,0,0.5\nP1,2,right,0,0.6\n"                    // zero duration: rejected
      "P1,3,right,0,0.5\nP1,3,right,1,0.5\nP1,3,right,2,0.5\n"  // never moves: scored
      "P1,4,right,0,0.5\nP1,4,right,1,1\n";                     // two samples: scored
  write_text(d / "log.csv", log);
  const auto r = run_feint("score " + shell_quote((d / "log.csv").string()) + " -o " +
                           shell_quote((d / "scores.csv").string()) +
                           " --confusion-norm raw --on-error skip");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("2 trials scored, 2 rejected"), std::string::npos) << r.err;
  const std::string rejects = read_text(d / "scores.csv.rejects.csv");
  EXPECT_NE(rejects.find("log.csv:2: 1 valid sample(s); a trial needs at least 2"),
            std::string::npos) << rejects;
  EXPECT_NE(rejects.find("(trial P1/1)"), std::string::npos) << rejects;
  EXPECT_NE(rejects.find("log.csv:4: column 't': 0 is not after the previous sample's 0"),
            std::string::npos) << rejects;
  EXPECT_NE(rejects.find("(trial P1/2)"), std::string::npos) << rejects;
  feint::io::CsvReader in((d / "scores.csv").string());
  ASSERT_TRUE(in.next());
  const auto f = [&](const char* name) { return std::string(in.field(static_cast<std::size_t>(in.column(name)))); };
  EXPECT_EQ(f("iteration"), "3");
  EXPECT_EQ(f("flips"), "0");
  EXPECT_EQ(f("time_deceived"), "0");
  EXPECT_EQ(f("max_deviation"), "0");
  EXPECT_EQ(f("final_belief_time"), "");  // never chose a side: empty, not 0
  ASSERT_TRUE(in.next());
  EXPECT_EQ(f("iteration"), "4");
  EXPECT_EQ(*feint::io::parse_double(f("final_belief_time")), 0.1);  // 0.5 -> 1 passes 0.55 at 0.1
  EXPECT_FALSE(in.next());
}
