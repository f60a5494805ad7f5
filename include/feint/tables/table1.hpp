// feint/tables/table1.hpp - the paper's Table 1: per iteration and metric, a t-test of the
// participants' values (one-sample against a reference mean, or condition A against B), with
// p-value adjustment within a metric column and optional TOST equivalence.
//
// statistics.md "Table 1". Rows of the paper-shaped table are iterations; per metric the mean(s),
// the p-value (and the adjusted one) and the inference label. Every test is also a tidy row.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "feint/io/scores.hpp"
#include "feint/models/condition_design.hpp"
#include "feint/tables/table1_conditions.hpp"
#include "feint/tables/tidy.hpp"
#include "feint/tables/writers.hpp"
#include "feint/stats/htest.hpp"
#include "feint/stats/p_adjust.hpp"

namespace feint::tables {

/// A metric column and its reference mean (one-sample mode).
struct MetricSpec {
  std::string column;
  double reference = 0.0;
  /// The confusion normalisation the reference is a value of ("raw" or "speed"); "" = the scale of
  /// the scores it is used with. Only confusion has scales (docs/metrics.md "One scale").
  std::string scale = {};
};

/// The paper's defaults: error against 0.5, confusion against 0.95 on the raw scale.
std::vector<MetricSpec> default_metrics();

/// Parses `--metric NAME=REF[@SCALE]` (REF a number; SCALE raw or speed, confusion only) or
/// `--metric NAME` (reference and scale from the defaults). Throws UsageError.
MetricSpec parse_metric_spec(std::string_view text);

/// The normalisation the scores' provenance records ("raw", "speed"), "" when unknown.
std::string scores_scale(const io::ScoresProvenance& provenance);

/// Refuses (UsageError, exit 64) a reference whose scale is not the scores' own: a reference of
/// one confusion normalisation tested against scores of another says nothing. `scale` is the
/// scores' normalisation ("" = unknown: nothing to check); `source` names the scores.
void check_reference_scales(const std::vector<MetricSpec>& metrics, std::string_view scale,
                            std::string_view source);

struct Table1Options {
  std::vector<MetricSpec> metrics = default_metrics();
  /// One-sample mode: test only this condition ("" = every condition, one block each).
  std::string condition;
  /// Two-sample mode when set: (A, B).
  std::optional<std::pair<std::string, std::string>> compare;
  bool var_equal = false;  ///< Student instead of Welch (two-sample)
  bool paired = false;     ///< paired t, pairs matched by participant (two-sample)
  double alpha = 0.05;
  stats::TestOptions test;  ///< alternative, conf_level
  stats::PAdjustMethod p_adjust = stats::PAdjustMethod::none;
  std::optional<double> equivalence;  ///< TOST margin delta (> 0)
  bool apa = false;                   ///< fill TidyRow::apa
  /// Scale r of the JZS Bayes factor's Cauchy prior (sqrt(2)/2 = BayesFactor's "medium").
  double bf_prior_r = 0.7071067811865476;
  /// Three or more conditions, one-sample mode with every condition: the omnibus comparison of the
  /// conditions per iteration (Table1::conditions; feint/tables/table1_conditions.hpp). How the
  /// conditions relate to the participants: declared, or nullopt = read off the data.
  std::optional<models::ConditionDesign> design;
  std::uint64_t omnibus_permutations = 9999;  ///< maxF relabellings drawn when not all enumerated
  std::uint64_t omnibus_seed = 20261126;      ///< their seed: the same p-values on every machine
};

/// One cell of the paper-shaped table: a metric at an iteration (in one condition, or A vs B).
struct Table1Cell {
  std::size_t difference_row = 0;          ///< index into Table1::rows
  std::optional<std::size_t> tost_row;     ///< index into Table1::rows (with --equivalence)
};

/// A block of the table: one condition (one-sample mode) or the comparison (two-sample mode).
struct Table1Block {
  std::string title;  ///< "adaptive" (one-sample, several conditions), "" otherwise
  std::string group1, group2;
  std::vector<long long> iterations;
  /// cells[i][m]: iteration i, metric m.
  std::vector<std::vector<Table1Cell>> cells;
};

struct Table1 {
  Table1Options options;
  std::string source;  ///< input path
  io::ScoresProvenance provenance;
  std::vector<TidyRow> rows;  ///< every test, tidy (difference tests and TOST rows)
  std::vector<Table1Block> blocks;
  std::vector<std::string> warnings;  ///< missing values, unpaired participants, ...
  /// Three or more conditions (one-sample mode, every condition): the omnibus comparison.
  std::optional<Table1Conditions> conditions;
};

/// Builds the table from a loaded scores table. Throws InvalidData for a metric not loaded, an
/// unknown condition in `condition`/`compare`, or a comparison of a condition with itself;
/// UsageError for impossible options (alpha, conf_level, delta out of range, no relabelling).
/// With three or more conditions in one-sample mode (no `condition`), also the omnibus comparison
/// of the conditions (Table1::conditions).
Table1 build_table1(const io::ScoresTable& scores, const Table1Options& options);

/// The note under the table: test, alternative, alpha, adjustment (family), reference means,
/// confusion normalisation, what the labels mean, non-computable tests and warnings.
std::vector<std::string> table1_note(const Table1& table);

/// Renders the paper-shaped table (text, markdown, latex) or the tidy rows (csv, json; with the
/// "apa" column when options.apa).
/// `presentation`: --label/--caption/--latex-wide; the default label is unique per table:
/// tab:feint-table1, tab:feint-table1-<condition> (--condition), tab:feint-table1-<A>-vs-<B>.
std::string render_table1(const Table1& table, OutputFormat format,
                          const TablePresentation& presentation = {});

/// The default LaTeX label of `table` (see render_table1).
std::string table1_default_label(const Table1& table);

}  // namespace feint::tables
