#include "analyze_anova.hpp"

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::cli {

std::optional<report::AnovaReport> analyze_anova(const io::ScoresTable& scores) {
  try {
    return report::build_anova_report(scores, models::SphericityCorrection::GG);
  } catch (const InvalidData& e) {
    fmt::print(stderr, "feint analyze: anova.* not written: {}\n", e.what());
    return std::nullopt;
  }
}

}  // namespace feint::cli
