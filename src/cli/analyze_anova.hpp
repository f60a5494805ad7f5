// src/cli/analyze_anova.hpp - the mixed ANOVA step of `feint analyze` (issue 10).
#pragma once

#include <optional>

#include "feint/io/scores.hpp"
#include "feint/report/anova_render.hpp"

namespace feint::cli {

/// The mixed ANOVA of every metric of the study's scores (GG correction, as afex), or nothing when
/// the design does not allow it (one iteration, a constant metric, ...): then a line on standard
/// error says why and the rest of the analysis goes on.
std::optional<report::AnovaReport> analyze_anova(const io::ScoresTable& scores);

}  // namespace feint::cli
