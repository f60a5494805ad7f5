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
  EXPECT_NE(text.out.find("Confusion normalisation: speed"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("scores.csv.meta.json"), std::string::npos) << text.out;
}
