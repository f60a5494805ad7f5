// feint/tables/table1_conditions.hpp - Table 1 with three or more conditions: per metric and
// iteration, the omnibus comparison of the conditions, and its family over the iterations
// (docs/tables.md "Three or more conditions").
//
// Two conditions are compared by `--compare A,B` (Welch's t, or the paired t within participants);
// three or more have no one pair to compare, so beside each condition's one-sample block Table 1
// tests whether the conditions differ at all, iteration by iteration:
//  - between participants: Welch's F (R's oneway.test(y ~ g), primary: as Welch's t is for two
//    conditions, it does not assume equal variances), the one-way ANOVA F (oneway.test(var.equal =
//    TRUE), = summary(aov(y ~ g))) with eta squared and omega squared and their one-sided intervals
//    (effectsize's eta_squared / omega_squared), and Kruskal–Wallis (kruskal.test) with the rank
//    epsilon squared;
//  - within participants (each participant saw every condition): the one-way repeated-measures F
//    on the participants with every condition at that iteration, Greenhouse–Geisser corrected
//    (primary: afex::aov_ez(within = "condition"), the correction feint anova applies), with afex's
//    generalized eta squared, and Friedman's test (friedman.test) with Kendall's W.
// The family: the primary tests of a metric over the iterations, adjusted by the Westfall–Young
// step-down maxF (stats::maxf_step_down_between / _within: participants relabelled between the
// conditions, or each participant's conditions permuted), as the per-iteration contrasts of two
// conditions are adjusted by maxT; `--p-adjust` adjusts every kind of test within its own family,
// as it does Table 1's other columns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/tables/tidy.hpp"
#include "feint/tables/writers.hpp"

namespace feint::tables {

struct Table1Options;  // feint/tables/table1.hpp

/// One omnibus test of a metric at an iteration, with the numbers the tidy columns do not hold.
struct OmnibusRow {
  /// test: welch_anova, anova, kruskal_wallis (between); rm_anova, friedman (within). group1 = the
  /// conditions joined by ", ", group2 empty. The label: "differ", "n.s." or "not computable".
  TidyRow row;
  bool primary = false;
  std::optional<double> p_maxf;  ///< primary rows: step-down maxF over the metric's iterations
  /// One-way ANOVA: omega squared (effectsize's, 0 when F < 1) and its one-sided interval.
  std::optional<double> omega_squared, omega_squared_low, omega_squared_high;
  std::optional<double> ges;                 ///< rm_anova: generalized eta squared (afex)
  /// rm_anova: ges's one-sided interval as effectsize's eta_squared(generalized = TRUE) gives it
  /// (stats::generalized_eta2 with the df uncorrected for sphericity); empty when ges = 1.
  std::optional<double> ges_low, ges_high;
  std::optional<double> sphericity_epsilon;  ///< rm_anova: the Greenhouse–Geisser epsilon applied
  std::optional<double> kendalls_w;          ///< friedman: Kendall's W
};

/// The maxF family of one metric: the relabellings counted, or why there is none.
struct OmnibusFamily {
  std::string metric;
  std::uint64_t labellings = 0;
  bool exact = false;  ///< every relabelling enumerated
  std::string note;    ///< non-empty: why the family p-values are missing
};

struct Table1Conditions {
  std::vector<std::string> conditions;  ///< the scores' order
  bool within = false;
  std::string design_note;  ///< how the design was decided (declared, or read off the data)
  std::vector<long long> iterations;
  std::vector<std::string> metrics;
  /// Per metric, per iteration: the primary test, then the others (rows_per_cell() in all).
  std::vector<OmnibusRow> rows;
  std::vector<OmnibusFamily> families;  ///< per metric
  std::vector<std::string> warnings;
  /// Non-empty: no omnibus comparison (the design could not be decided), and why.
  std::string not_computed;

  std::size_t rows_per_cell() const noexcept { return within ? 2 : 3; }
  /// The primary row of metric m at iteration i.
  const OmnibusRow& primary(std::size_t i, std::size_t m) const {
    return rows[(m * iterations.size() + i) * rows_per_cell()];
  }
};

/// The omnibus comparison of the conditions of `scores` (three or more) for the metrics of
/// `options`: Table1Options::design (nullopt = read off the data, as feint table does), alpha,
/// conf_level, p_adjust, apa, omnibus_permutations and omnibus_seed. A design the data leave
/// unclear gives a table with `not_computed` set, never an exception.
Table1Conditions build_table1_conditions(const io::ScoresTable& scores, const Table1Options& options);

/// The paper-shaped table of `c` (text, markdown, latex) with its note, LaTeX label `latex_label`
/// (`table*` when `latex_wide`). Throws std::invalid_argument for csv/json.
std::string render_table1_conditions(const Table1Conditions& c, const Table1Options& options, OutputFormat format,
                                     const std::string& latex_label, bool latex_wide = false);

/// The tidy columns the omnibus rows add after Table 1's (and its "apa"): df2, p_maxf, the effect
/// sizes and their intervals, ges, sphericity_epsilon, rank_epsilon_squared, kendalls_w.
std::vector<std::string_view> table1_conditions_columns();

/// Table 1's tidy rows followed by the omnibus rows, as CSV or JSON records with `columns` and
/// then table1_conditions_columns() (empty cells where a column does not apply).
std::string render_table1_with_conditions(std::span<const TidyRow> rows, const Table1Conditions& c,
                                          std::span<const std::string_view> columns, OutputFormat format);

}  // namespace feint::tables
