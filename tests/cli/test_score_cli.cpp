// End-to-end tests of `feint score` (runs FEINT_EXE).
#include <gtest/gtest.h>

#include "cli/cli_helpers.hpp"

using feint::test::run_feint;

TEST(CliHelpers, CapturesExitCodeAndStreams) {
  const auto help = run_feint("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("score"), std::string::npos);
  const auto bad = run_feint("--no-such-option");
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_FALSE(bad.err.empty());
}
