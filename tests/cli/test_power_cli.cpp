// End-to-end tests of `feint power t-test` and `feint power simulate`.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"

using feint::test::run_feint;
using feint::test::RunResult;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

std::map<std::string, std::string> first_record(const std::string& csv) {
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  const auto h = feint::io::split_csv_line(header);
  const auto f = feint::io::split_csv_line(line);
  std::map<std::string, std::string> out;
  for (std::size_t i = 0; i < h.size() && i < f.size(); ++i) out[h[i]] = f[i];
  return out;
}

TEST(PowerCli, SampleSizeOfTheClassicExampleMatchesPowerTTest) {
  // R: power.t.test(delta = 0.5, power = 0.8, strict = TRUE, tol = 1e-13)$n = 63.765610190941892
  const RunResult r = run_feint("power t-test --d 0.5 --power 0.8 --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rec = first_record(r.out);
  EXPECT_EQ(rec.at("solved"), "n");
  EXPECT_EQ(rec.at("n1_ceiling"), "64");
  EXPECT_GE(std::stod(rec.at("power_at_ceiling")), 0.8);
  EXPECT_NEAR(std::stod(rec.at("n1")), 63.765610190941892, 1e-8);
}

TEST(PowerCli, BonferroniOverTwentyTestsRaisesTheSampleSize) {
  const RunResult one = run_feint("power t-test --d 0.5 --power 0.8 --format json");
  const RunResult twenty = run_feint("power t-test --d 0.5 --power 0.8 --tests 20 --format json");
  ASSERT_EQ(twenty.exit_code, 0) << twenty.err;
  EXPECT_NE(twenty.out.find("\"alpha_per_test\": 0.0025"), std::string::npos) << twenty.out;
  EXPECT_NE(one.out, twenty.out);
}

TEST(PowerCli, BadRequestsExit64) {
  RunResult r = run_feint("power t-test --d 0.5");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("give exactly two of --n, --delta (or --d) and --power"), std::string::npos)
      << r.err;
  r = run_feint("power t-test --d 0.5 --delta 0.4 --n 10");
  EXPECT_EQ(r.exit_code, 64);
  r = run_feint("power t-test --type three-sample --d 0.5 --n 10");
  EXPECT_EQ(r.exit_code, 64);
  r = run_feint("power simulate --means-a 0.5,0.5 --means-b 0.5 --sd-residual 0.1");
  EXPECT_EQ(r.exit_code, 64);
}

TEST(PowerCli, SimulationFromAPilotIsReproducibleFromItsSeed) {
  TempDir dir;
  const auto pilot = dir.path() / "pilot.csv";
  std::string text = "participant,condition,iteration,error\n";
  for (int i = 0; i < 10; ++i) {
    for (int j = 1; j <= 4; ++j) {
      const double v =
          (i < 5 ? 0.6 : 0.5) + 0.01 * ((i * 7 + j * 3) % 5) - (i < 5 ? 0.0 : 0.02 * j);
      text += "P" + std::to_string(i) + "," + (i < 5 ? "A" : "B") + "," + std::to_string(j) + "," +
              std::to_string(v) + "\n";
    }
  }
  write_text(pilot, text);
  const std::string cmd = "power simulate " + shell_quote(pilot.string()) +
                          " --studies 300 --seed 9 --n-per-group 12 --format csv";
  const RunResult a = run_feint(cmd);
  const RunResult b = run_feint(cmd + " --threads 1");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  const auto rec = first_record(a.out);
  EXPECT_EQ(rec.at("test"), "condition:iteration (mixed ANOVA, GG)");
  EXPECT_EQ(rec.at("n_a"), "12");
  EXPECT_EQ(rec.at("studies"), "300");
  const RunResult text_out =
      run_feint("power simulate " + shell_quote(pilot.string()) + " --studies 50");
  EXPECT_NE(text_out.out.find("Design from pilot"), std::string::npos) << text_out.out;
}

TEST(PowerCli, PilotWithOneConditionExits65) {
  TempDir dir;
  const auto pilot = dir.path() / "pilot.csv";
  write_text(
      pilot,
      "participant,iteration,error\nP1,1,0.1\nP1,2,0.3\nP2,1,0.2\nP2,2,0.5\nP3,1,0.3\nP3,2,0.2\n");
  const RunResult r = run_feint("power simulate " + shell_quote(pilot.string()) + " --studies 10");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("simulation power needs exactly two"), std::string::npos) << r.err;
}

}  // namespace
