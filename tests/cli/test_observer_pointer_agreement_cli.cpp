// `feint observer fit` on logs of K targets and a pointer shows the learning test and the
// model-human agreement table, as for pads (docs/observer.md, "Agreement and learning on pointer
// traces"), in text and JSON, and `--no-learning` skips the test.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "cli_helpers.hpp"

using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const char* kHeader =
    "participant,condition,iteration,strategy,variant,target,t,belief_x,belief_y,start_x,start_y,target0_x,"
    "target0_y,target1_x,target1_y,target2_x,target2_y,robot_x,robot_y\n";

/// One trial: the robot straight from (0, 0) to target 2 at (2, 4), the pointer straight from
/// (0.3, 4.2) to (1.8, 4.1) at a constant speed, 20 samples 0.5 s apart.
std::string trial_rows(const std::string& participant, int iteration, const std::string& strategy) {
  std::string rows;
  const int n = 20;
  for (int i = 0; i < n; ++i) {
    const double f = static_cast<double>(i) / (n - 1);
    rows += participant + ",c," + std::to_string(iteration) + "," + strategy + ",main,2," + std::to_string(0.5 * i) +
            "," + std::to_string(0.3 + 1.5 * f) + "," + std::to_string(4.2 - 0.1 * f) + ",0,0,-2,4,0,4,2,4," +
            std::to_string(2 * f) + "," + std::to_string(4 * f) + "\n";
  }
  return rows;
}

/// The human error of every trial, computed here: the pointer's mean distance to (2, 4) over the
/// middle 90 % of the trial (5 % trimmed at each end), in layout scales (4 m: from target 0 to 2),
/// by Simpson's rule on a straight segment traversed at a constant speed.
double human_error() {
  const int m = 20000;
  auto d = [](double f) { return std::hypot(0.3 + 1.5 * f - 2, 4.2 - 0.1 * f - 4) / 4; };
  double s = 0;
  for (int k = 0; k <= m; ++k) {
    const double f = 0.05 + 0.9 * k / m;
    s += (k == 0 || k == m ? 1 : (k % 2 ? 4 : 2)) * d(f);
  }
  return s / (3.0 * m);
}

}  // namespace

TEST(ObserverFitPointerCli, ShowsTheLearningTestAndTheAgreementTable) {
  TempDir dir;
  for (const char* p : {"P1", "P2"}) {
    std::string log = kHeader;
    for (int it = 1; it <= 4; ++it) log += trial_rows(p, it, it % 2 ? "optimal" : "exaggerating");
    write_text(dir / "logs" / (std::string(p) + ".csv"), log);
  }
  const std::string logs = shell_quote((dir / "logs").string());
  const auto r = run_feint("observer fit " + logs);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto learning = r.out.find("\nLearning: beta_k = beta0 exp(gamma exposure_k)");
  const auto table = r.out.find("\nModel-human agreement (model mean m(t) at each participant's fit vs the pointer");
  ASSERT_NE(learning, std::string::npos) << r.out;
  ASSERT_NE(table, std::string::npos) << r.out;
  EXPECT_LT(r.out.find("\nPooled per condition"), learning);
  EXPECT_LT(learning, table);
  EXPECT_EQ(r.out.find("No model-human agreement table"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  c          gamma = "), std::string::npos) << r.out;
  // The margins: every trial in "all" x "all" x every iteration; each strategy has 4.
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\nall +all +all +8  ")));
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\nc +optimal +all +4  ")));

  const auto j = run_feint("observer fit " + logs + " -f json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const auto jl = j.out.find("\"learning\": [\n    {\"condition\": \"c\", \"gamma\": {\"estimate\": ");
  const auto ja = j.out.find("\"agreement\": [\n    {\"condition\": \"all\", \"strategy\": \"all\", \"iteration\": null, "
                             "\"trials\": 8, \"human_error\": ");
  ASSERT_NE(jl, std::string::npos) << j.out;
  ASSERT_NE(ja, std::string::npos) << j.out;
  EXPECT_LT(j.out.find("\"conditions\": "), jl);
  EXPECT_LT(jl, ja);
  EXPECT_LT(ja, j.out.find("\"comparisons\": "));
  // The human's error and confusion do not depend on the fit: the pointer approaches the target
  // without a reversal (confusion 0), its error is the trimmed mean distance computed here.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(j.out, m,
                                std::regex("\"trials\": 8, \"human_error\": ([-0-9.e]+), .*?\"human_confusion\": "
                                           "([-0-9.e]+),")));
  EXPECT_NEAR(std::stod(m[1]), human_error(), 1e-6);
  EXPECT_EQ(std::stod(m[2]), 0.0);

  const auto off = run_feint("observer fit " + logs + " --no-learning");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_EQ(off.out.find("Learning:"), std::string::npos) << off.out;
  EXPECT_NE(off.out.find("Model-human agreement"), std::string::npos);
}
