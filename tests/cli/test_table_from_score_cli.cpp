// End-to-end: pad traces -> `feint score` -> `feint table`. The table reads what score wrote,
// including its sidecar (the note says how confusion was normalised).
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

// One trial: 11 samples at t = 0..10 of a pad path that goes toward `away` and ends at the target.
std::string trial(const std::string& participant, int iteration, double away) {
  std::string s;
  const std::vector<double> shape = {0.5, 0.5 - away / 2, 0.5 - away, 0.5 - away, 0.5 - away / 2,
                                     0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  for (int i = 0; i <= 10; ++i) {
    s += participant + ",adaptive," + std::to_string(iteration) + ",exaggerating,main,right," +
         std::to_string(i) + "," + feint::io::format_double(shape[static_cast<std::size_t>(i)]) +
         ",0.25\n";
  }
  return s;
}

}  // namespace

TEST(TableFromScoreCli, TabulatesWhatScoreWroteAndCitesItsSidecar) {
  TempDir d;
  std::string log = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  const std::vector<double> away = {0.1, 0.3, 0.2, 0.4};
  for (int p = 0; p < 4; ++p) {
    for (int it = 1; it <= 2; ++it) {
      log += trial("P0" + std::to_string(p + 1), it, away[static_cast<std::size_t>(p)] / it);
    }
  }
  write_text(d / "log.csv", log);
  const auto scored = run_feint("score " + shell_quote((d / "log.csv").string()) + " -o " +
                                shell_quote((d / "scores.csv").string()));
  ASSERT_EQ(scored.exit_code, 0) << scored.err;

  // The mean error at iteration 1, from the scores file itself.
  feint::io::CsvReader scores((d / "scores.csv").string());
  const int ie = scores.column("error"), ii = scores.column("iteration");
  ASSERT_GE(ie, 0);
  double sum = 0;
  int n = 0;
  while (scores.next()) {
    if (scores.field(static_cast<std::size_t>(ii)) != "1") continue;
    sum += *feint::io::parse_double(scores.field(static_cast<std::size_t>(ie)));
    ++n;
  }
  ASSERT_EQ(n, 4);

  const auto r = run_feint("table " + shell_quote((d / "scores.csv").string()) + " --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto pos = r.out.find("\nerror,1,one_sample_t,One Sample t-test,two.sided,0.5,adaptive,,4,,");
  ASSERT_NE(pos, std::string::npos) << r.out;
  const auto start = pos + std::string("\nerror,1,one_sample_t,One Sample t-test,two.sided,0.5,adaptive,,4,,").size();
  const double mean1 = *feint::io::parse_double(r.out.substr(start, r.out.find(',', start) - start));
  EXPECT_NEAR(mean1, sum / n, 1e-15);

  const auto text = run_feint("table " + shell_quote((d / "scores.csv").string()));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  // The default normalisation is raw, the scale of the default reference 0.95 (docs/metrics.md).
  EXPECT_NE(text.out.find("Confusion normalisation: raw"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("confusion R = 0.95 on the raw scale"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("scores.csv.meta.json"), std::string::npos) << text.out;
}

// One scale (docs/metrics.md "One scale"): a reference of one confusion normalisation with scores
// of the other is refused at load with the fix, never tested; a reference on the scores' own
// scale, or one without a scale, is used.
TEST(TableFromScoreCli, AReferenceOfAnotherScaleIsRefusedWithTheFix) {
  TempDir d;
  std::string log = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
  for (int p = 0; p < 3; ++p) log += trial("P0" + std::to_string(p + 1), 1, 0.1 * (p + 1));
  write_text(d / "log.csv", log);
  const std::string scores = shell_quote((d / "speed.csv").string());
  const auto scored = run_feint("score " + shell_quote((d / "log.csv").string()) +
                                " --confusion-norm speed -o " + scores);
  ASSERT_EQ(scored.exit_code, 0) << scored.err;

  const auto by_default = run_feint("table " + scores);  // the default 0.95 is a raw value
  EXPECT_EQ(by_default.exit_code, 64) << by_default.out;
  EXPECT_NE(by_default.err.find("confusion is on the speed scale but its reference 0.95 is a value "
                                "of the raw scale"),
            std::string::npos)
      << by_default.err;
  EXPECT_NE(by_default.err.find("--confusion-norm raw"), std::string::npos) << by_default.err;
  EXPECT_NE(by_default.err.find("--metric confusion=VALUE@speed"), std::string::npos) << by_default.err;
  EXPECT_EQ(by_default.out, "");

  const auto explicit_raw = run_feint("table " + scores + " --metric confusion=0.95@raw");
  EXPECT_EQ(explicit_raw.exit_code, 64);
  EXPECT_EQ(run_feint("table " + scores + " --metric confusion=0.3@speed").exit_code, 0);
  EXPECT_EQ(run_feint("table " + scores + " --metric confusion=0.3").exit_code, 0);  // the scores' scale
  const auto bad = run_feint("table " + scores + " --metric error=0.5@raw");
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_NE(bad.err.find("only confusion has scales"), std::string::npos) << bad.err;
  const auto typo = run_feint("table " + scores + " --metric confusion=0.3@sped");
  EXPECT_EQ(typo.exit_code, 64);
  EXPECT_NE(typo.err.find("expected raw or speed"), std::string::npos) << typo.err;
}
