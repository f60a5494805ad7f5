// --contrasts / --adjust / --ddf of `feint anova` and `feint model` (feint/models/emmeans.hpp):
// families in the order asked, each once; every refusal names the option.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "feint/error.hpp"
#include "feint/models/emmeans.hpp"

using namespace feint::models;

TEST(EmmContrastOptions, FamiliesInTheOrderAskedEachOnce) {
  const auto r = parse_emm_contrasts({"simple", "pairwise", "simple"}, "");
  const std::vector<EmmFamily> want = {
      EmmFamily::condition_at_iteration, EmmFamily::iteration_in_condition,
      EmmFamily::pairwise_condition, EmmFamily::pairwise_iteration};
  EXPECT_EQ(r.families, want);
  EXPECT_FALSE(r.adjust.has_value());
  const auto h = parse_emm_contrasts({"poly"}, "holm");
  ASSERT_TRUE(h.adjust.has_value());
  EXPECT_EQ(*h.adjust, EmmAdjust::holm);
}

TEST(EmmContrastOptions, RefusalsNameTheOption) {
  auto message = [](const std::vector<std::string>& c, const std::string& a) {
    try {
      parse_emm_contrasts(c, a);
    } catch (const feint::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(message({"helmert"}, ""), "--contrasts helmert: expected pairwise, simple or poly");
  EXPECT_EQ(message({}, "holm"), "--adjust applies to --contrasts");
  EXPECT_EQ(message({"pairwise", "poly"}, "tukey"),
            "--adjust tukey applies to pairwise and simple contrasts, not to poly");
  EXPECT_EQ(parse_ddf_method("kenward-roger"), DdfMethod::kenward_roger);
  EXPECT_THROW(parse_ddf_method("kr"), feint::UsageError);
}
