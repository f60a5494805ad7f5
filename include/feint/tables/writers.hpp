// feint/tables/writers.hpp - renderings shared by every report: tidy CSV/JSON, number and p-value
// formatting, APA strings, inference labels, and a small aligned-table renderer (text, Markdown,
// LaTeX/booktabs).
//
// One result type (stats::TestResult), many renderings: `feint table`, `feint likert` and
// `feint describe` all go through these functions, so a p-value or a "not computable" test looks the
// same everywhere.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/tables/tidy.hpp"
#include "feint/stats/htest.hpp"

namespace feint::tables {

// ---------------------------------------------------------------------------------------------
// Output formats

enum class OutputFormat { text, markdown, latex, csv, json };

/// "text", "markdown" (also "md"), "latex" (also "tex"), "csv", "json"; case-insensitive.
/// Throws UsageError otherwise.
OutputFormat parse_output_format(std::string_view name);
std::string_view to_string(OutputFormat format) noexcept;

// ---------------------------------------------------------------------------------------------
// Number formatting

/// Fixed 4 decimals as in the paper's Table 1 (`0.5703`); empty value -> "". Never "-0.0000".
std::string format_mean(std::optional<double> value, int decimals = 4);

/// How a p-value is shown in a table (`format_p`).
enum class PStyle {
  plain,  ///< `0.0066`, `1.5e-04`, `< 2.2e-308` (terminal, Markdown, CSV-friendly text)
  latex,  ///< `0.0066`, `$1.5 \times 10^{-4}$`, `$< 2.2 \times 10^{-308}$`
};

/// A p-value for a table: 4 decimals when p >= 1e-3; scientific notation with two significant
/// digits below (the paper prints 1.5*10^-4); `< 2.2e-308` when p is below the smallest positive
/// normal double (including an underflowed 0), never 0. Empty value -> "".
std::string format_p(std::optional<double> p, PStyle style = PStyle::plain);

/// Full-precision number for tidy output (io::format_double: shortest round trip); empty -> "".
std::string format_full(std::optional<double> value);

// ---------------------------------------------------------------------------------------------
// APA strings

/// APA-style p: `p = .007`, `p < .001`, `p > .999`; no leading zero; three decimals.
std::string apa_p(double p);

/// APA-style summary of any TestResult, e.g. `t(29) = 2.93, p = .007, d = 0.53` (t tests; Welch df
/// with two decimals), `V = 120, p = .003, r = .62` (Wilcoxon signed-rank), `W = 310.5, p = .041,
/// r = -.27` (Mann-Whitney), `F(2, 57) = 3.41, p = .040, η² = .11` (ANOVA, η² = R² when known;
/// Welch denominator df with two decimals), `χ²(2) = 5.21, p = .074` (Kruskal-Wallis), and for TOST
/// `TOST: t(29) = 2.10, p = .022`. An adjusted p is added as `, adjusted p = .021`. A test that
/// could not be computed gives `not computable: <reason>`.
std::string apa_string(const stats::TestResult& result);

// ---------------------------------------------------------------------------------------------
// Inference labels (statistics.md, "Table 1")

/// Which p a label uses: the adjusted one when a multiple-comparison adjustment was made.
std::optional<double> decision_p(const stats::TestResult& result) noexcept;

inline constexpr std::string_view kApprox = "\u2248";  // "≈"
/// The label of a test that is neither significant nor evidence of no difference: the same word in
/// every command, table format, figure legend and report (docs/tables.md "Labels").
inline constexpr std::string_view kNotSignificant = "n.s.";
/// BF01 >= 3: moderate evidence for no difference, the least that earns "≈" without TOST.
inline constexpr double kBf01Equivalence = 3.0;
inline constexpr std::string_view kNotComputable = "not computable";

/// The inference label of a difference test, `lhs` and `rhs` being the two sides' names (`M`/`R`
/// for one-sample tests against a reference, `A`/`B` for two conditions):
///  - not computed: "not computable";
///  - p (adjusted when present) < alpha: `lhs>rhs` or `lhs<rhs` by the sign of estimate - mu;
///  - otherwise `lhs≈rhs` only from evidence of no difference: the test's JZS Bayes factor BF01 >= 3
///    (`difference.log_bf10 <= -log 3`) or, with an equivalence test (`tost` non-null), its TOST p
///    (adjusted when present) < alpha;
///  - otherwise "n.s." (or "not computable" when the requested TOST could not be computed).
/// "≈" therefore never means only "not significantly different".
std::string inference_label(const stats::TestResult& difference, double alpha, std::string_view lhs,
                            std::string_view rhs, const stats::TestResult* tost = nullptr);

/// One-sample labels: `M>R`, `M<R`, `M≈R`, "n.s.".
std::string one_sample_label(const stats::TestResult& difference, double alpha,
                             const stats::TestResult* tost = nullptr);
/// Two-sample labels: `A>B`, `A<B`, `A≈B`, "n.s." (A = group 1, B = group 2).
std::string two_sample_label(const stats::TestResult& difference, double alpha,
                             const stats::TestResult* tost = nullptr);

// ---------------------------------------------------------------------------------------------
// Tidy records (CSV / JSON)

/// One cell of a tidy record: empty (CSV "", JSON null), text (quoted), or a number already
/// formatted as JSON-compatible text (written unquoted in JSON).
struct Cell {
  enum class Kind { empty, text, number, boolean };
  Kind kind = Kind::empty;
  std::string text;

  static Cell none() { return {}; }
  static Cell str(std::string s) { return {Kind::text, std::move(s)}; }
  static Cell num(std::optional<double> v);  ///< full precision; empty when nullopt
  static Cell integer(long long v) { return {Kind::number, std::to_string(v)}; }
  static Cell flag(std::optional<bool> v) {
    return v ? Cell{Kind::boolean, *v ? "true" : "false"} : Cell{};
  }
};

using Record = std::vector<Cell>;

/// The value of `column` for a tidy row. Known columns: kTableColumns, kLikertExtraColumns and
/// "apa". Throws std::invalid_argument for any other name (a programming error).
/// A Bayes factor for a sentence: "BF₁₀ = 3.21" when log BF10 >= 0, else "BF₀₁ = 4.50" (the
/// direction of the evidence); values >= 1000 in scientific notation ("BF₁₀ = 2.3e+05").
std::string apa_bayes_factor(double log_bf10);

Cell tidy_cell(const TidyRow& row, std::string_view column);

/// Tidy records of `rows` restricted to `columns`, in order.
std::vector<Record> tidy_records(std::span<const TidyRow> rows,
                                 std::span<const std::string_view> columns);

/// kTableColumns, plus "apa" when asked for (`--apa`).
std::vector<std::string_view> table_columns(bool apa = false);
/// kTableColumns + kLikertExtraColumns, plus "apa" when asked for.
std::vector<std::string_view> likert_columns(bool apa = false);

/// RFC 4180 CSV: a header line with `columns`, one line per record, LF line ends.
std::string write_csv(std::span<const std::string_view> columns, std::span<const Record> records);
/// A JSON array of objects (keys = `columns`, in order); empty cells are null, numbers unquoted,
/// booleans true/false. Ends with a newline.
std::string write_json(std::span<const std::string_view> columns, std::span<const Record> records);

/// Convenience: tidy CSV / JSON of test rows.
std::string tidy_csv(std::span<const TidyRow> rows, std::span<const std::string_view> columns);
std::string tidy_json(std::span<const TidyRow> rows, std::span<const std::string_view> columns);

/// Escapes LaTeX special characters (& % $ # _ { } ~ ^ \ < >) in plain text; "x" becomes ``x''
/// and a few symbols (≈ ± × α δ η χ ² – — ≤ ≥) their LaTeX forms.
std::string latex_escape(std::string_view text);
/// Display width of UTF-8 text in a terminal (code points; "≈" counts 1).
std::size_t display_width(std::string_view utf8) noexcept;

// ---------------------------------------------------------------------------------------------
// Aligned tables for people (text, Markdown, LaTeX)

/// A rectangular table of already-formatted cells with optional column groups above the header
/// (as the paper's "Error (Reference Mean (R) = 0.5)" spanning Mean/P Value/Inference) and optional
/// section rows (e.g. "Condition: adaptive") between blocks of body rows.
struct TextTable {
  struct Group {
    std::string title;      ///< plain text (escaped for LaTeX by the renderer)
    std::size_t first = 0;  ///< first column spanned
    std::size_t count = 1;  ///< number of columns spanned
  };
  struct Row {
    std::vector<std::string> cells;  ///< plain text
    bool section = false;            ///< a full-width section heading (cells[0] is its title)
  };
  std::string caption;               ///< plain text; text/Markdown: a line above, LaTeX: \caption
  std::vector<Group> groups;
  std::vector<std::string> header;   ///< plain text
  std::vector<bool> right_align;     ///< per column (numbers right-aligned); default left
  std::vector<Row> rows;
  std::vector<std::string> notes;    ///< paragraphs of the note below the table (plain text)
  std::string latex_label;           ///< \label{...} when non-empty
  bool latex_wide = false;           ///< LaTeX `table*`: spans both columns of a two-column paper

  /// Cells that are already LaTeX (e.g. format_p(..., PStyle::latex)): rendered verbatim in LaTeX
  /// output instead of being escaped. Indexed [row][column]; may be empty (= escape everything).
  std::vector<std::vector<std::string>> latex_cells;
};

/// How the user wants a report's tables presented (`--label`, `--caption`, `--latex-wide`).
struct TablePresentation {
  std::string label;    ///< LaTeX \label of the main table; "" = the report's default
  std::string caption;  ///< caption of the main table (every format); "" = the report's own
  bool wide = false;    ///< LaTeX `table*` (both columns of a two-column paper) instead of `table`
};

/// Checks a `--label` value: letters, digits and `:-_./+` only (anything else breaks \label or
/// \ref). Throws UsageError.
void validate_latex_label(std::string_view label);

/// A LaTeX label fragment from free text (a condition name): letters and digits kept, every other
/// run of characters becomes one '-'.
std::string latex_label_part(std::string_view text);

/// Applies `p` to the main table `t` (label, caption) and marks it wide; `default_label` is used
/// when p.label is empty.
void apply_presentation(TextTable& t, const TablePresentation& p, std::string_view default_label);

/// Renders `table` as aligned plain text, a Markdown pipe table, or a LaTeX booktabs `table`
/// environment (a fragment for a paper: needs \usepackage{booktabs}). Throws std::invalid_argument
/// for csv/json.
std::string render_table(const TextTable& table, OutputFormat format);

}  // namespace feint::tables
