// feint/tables/anova.hpp - the mixed ANOVA of a scores table (or, with conditions within
// participants, the all-within ANOVA), rendered as text, Markdown, booktabs LaTeX, tidy CSV and
// JSON (docs/anova-power.md).
//
// Tidy columns follow afex's anova_table (spaces and R's `Pr(>F)` made syntactic, as broom):
// metric, effect, num_df, den_df, MSE, F, ges, pes, p.value (under the chosen correction), then
// correction, eps, the uncorrected df and p, both epsilons and their p, Mauchly's W and p, the sums
// of squares, n, excluded and note.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/models/emmeans.hpp"
#include "feint/models/mixed_anova.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

/// `feint anova --emmeans / --contrasts / --adjust`: emmeans on the afex object (its default
/// multivariate model; models/emmeans.hpp).
struct AnovaEmmOptions {
  bool emmeans = false;
  std::vector<models::EmmFamily> families;
  std::optional<models::EmmAdjust> adjust;  ///< empty: tukey for pairwise, none for poly
  double conf_level = 0.95;
  bool any() const { return emmeans || !families.empty(); }
};

struct AnovaReport {
  std::string source;  ///< the scores file
  models::SphericityCorrection correction = models::SphericityCorrection::GG;
  std::vector<models::MixedAnova> analyses;  ///< one per metric, in the order asked for
  AnovaEmmOptions emm_options;
  /// Per analysis: the tables of means and of each contrast family (empty without the options).
  std::vector<std::vector<models::EmmTable>> emm;
};

/// The observations of `metric` in `scores` (models::Observation rows, file order).
std::vector<models::Observation> observations(const io::ScoresTable& scores,
                                              const std::string& metric);

/// The mixed ANOVA of every metric of `scores` (InvalidData from make_wide_design/mixed_anova;
/// a condition left without complete participants stops it unless `drop_empty_conditions`).
/// `condition_within`: every participant sees every condition, and each metric gets the
/// all-within ANOVA instead (models::make_within_design + models::within_anova, as afex::aov_ez
/// with within = c("condition", "iteration")); `drop_empty_conditions` does not apply, and
/// estimated marginal means are not available yet (UsageError when `emm` asks for them).
AnovaReport build_anova_report(const io::ScoresTable& scores,
                               models::SphericityCorrection correction,
                               bool drop_empty_conditions = false,
                               const AnovaEmmOptions& emm = {}, bool condition_within = false);

/// `F(1.93, 112.1) = 4.31, p = .017, ηG² = .031`: df as reported (non-integer df with two
/// decimals below 100, one above), F two decimals, APA p, ges three decimals without leading zero.
std::string anova_apa(const models::AnovaEffect& effect);

/// Column names of the tidy CSV/JSON (plus "apa" when asked for).
std::vector<std::string_view> anova_columns(bool apa = false);

/// The report in `format`; `apa` adds an APA column (text/Markdown/LaTeX) or field (CSV/JSON).
/// `presentation` (--label, --caption, --latex-wide) applies to its one table (every metric is a
/// section of it); default label "tab:feint-anova".
std::string render_anova(const AnovaReport& report, OutputFormat format, bool apa = false,
                         const TablePresentation& presentation = {});

}  // namespace feint::tables
