// feint/io/questionnaire.hpp - Likert questionnaires: long, wide and survey-platform CSV.
//
// formats.md (Questionnaires): long `participant, [condition], item, response`; wide
// `participant, [condition], <item>...` (one row per respondent); Qualtrics exports (three header
// rows: names, question text, `{"ImportId": ...}`) have the two extra rows recognised and skipped.
// Text answers are mapped by a label map (the user's, or a built-in 5-/7-point agree/disagree map),
// matched case-insensitively after trimming. A response outside the scale or not a whole number is
// invalid data; an empty response is missing (excluded from that item only, and counted).
// Reverse-coded items are recoded x -> min + max - x right here, before any analysis.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace feint::io {

enum class QuestionnaireLayout { automatic, long_format, wide_format };

/// "auto", "long", "wide"; parse throws UsageError on anything else.
std::string_view to_string(QuestionnaireLayout layout) noexcept;
QuestionnaireLayout parse_questionnaire_layout(std::string_view text);

/// One entry of a label map: answer text -> scale point.
struct LabelEntry {
  std::string text;
  int value = 0;
};

struct QuestionnaireOptions {
  QuestionnaireLayout layout = QuestionnaireLayout::automatic;
  int scale_min = 1;  ///< lowest scale point (whole number)
  int scale_max = 7;  ///< highest scale point
  std::string id_column = "participant";
  std::string condition_column = "condition";  ///< optional; absent = one condition for everybody
  std::string item_column = "item";            ///< long layout
  std::string response_column = "response";    ///< long layout
  /// The items to use, in this order (wide: columns; long: values of the item column, rows of other
  /// items skipped). `name=Q5_1` renames: column (or long-layout item) Q5_1 becomes item `name`
  /// (--reverse and composites then use the new name). Empty = every item; in the wide layout
  /// every column that is not the id, the condition, or a known survey-platform metadata column
  /// (Qualtrics, Google Forms).
  std::vector<std::string> items;
  /// Label map for text answers. Empty = the built-in agree/disagree map when the scale has 5 or 7
  /// points (and no text answers accepted otherwise).
  std::vector<LabelEntry> labels;
  /// Items to reverse-code (x -> min + max - x), by name (case-insensitive).
  std::vector<std::string> reverse;
  char delimiter = 0;  ///< 0 = detect
  /// Survey exports (Qualtrics: the three header rows, or a ResponseId column): responses whose
  /// `Finished` is False/0 or whose `Progress` is below 100 are excluded unless this is set.
  bool keep_unfinished = false;
  /// Survey exports: responses whose `Status` is Survey Preview, Survey Test, Spam, Preview Spam,
  /// Imported Spam or Offline Preview (or their numeric codes 1, 2, 8, 9, 12, 17) are excluded
  /// unless this is set.
  bool keep_previews = false;
};

/// A survey-export row that is not a participant's response (see QuestionnaireOptions).
struct ExcludedResponse {
  std::size_t line = 0;
  std::string id;      ///< the respondent id (ResponseId), or "line N" when empty
  std::string reason;  ///< "Survey Preview", "Spam", "unfinished (Finished False, Progress 40)"
};

/// A loaded questionnaire: one column of responses per item, one entry per respondent.
/// A respondent is a (participant, condition) pair.
struct Questionnaire {
  std::string source;                                             ///< file name as given
  QuestionnaireLayout layout = QuestionnaireLayout::wide_format;  ///< the layout actually read
  bool qualtrics = false;  ///< the two extra Qualtrics header rows were recognised and skipped
  int scale_min = 1;
  int scale_max = 7;
  bool has_condition = false;  ///< the file has a condition column

  std::vector<std::string> items;         ///< item names, in file order
  std::vector<std::string> item_columns;  ///< wide: the column each item came from (= items)
  std::vector<bool> reversed;             ///< per item: was reverse-coded
  std::vector<std::string> participants;  ///< per respondent
  std::vector<std::string> conditions;    ///< per respondent ("" when no condition column)
  /// responses[item][respondent], after reverse coding; nullopt = missing (empty answer, or in the
  /// long layout no row for that item).
  std::vector<std::vector<std::optional<int>>> responses;

  std::size_t rows_read = 0;            ///< data rows read (Qualtrics' extra header rows excluded)
  std::size_t text_answers_mapped = 0;  ///< answers given as text and mapped by the label map
  std::string label_map;  ///< "", "user", "built-in 5-point agree", "built-in 7-point agree"
  /// Survey-export rows excluded as previews, tests, spam or unfinished (in file order); they are
  /// counted in rows_read but are not respondents.
  std::vector<ExcludedResponse> excluded;

  /// Index of an item (case-insensitive); nullopt when absent.
  std::optional<std::size_t> item_index(std::string_view name) const;
  /// Condition names in order of first appearance.
  std::vector<std::string> condition_names() const;
  std::size_t respondents() const noexcept { return participants.size(); }
  /// Missing responses of item `i`.
  std::size_t missing(std::size_t i) const;
};

/// Reads a questionnaire. Throws IoError when the file cannot be read, InvalidData on a contract
/// violation (message `file:line: column 'trust': 9 is outside the scale 1-7 (participant P07)`),
/// UsageError when an option names a column or item the file does not have.
Questionnaire load_questionnaire(const std::string& path, const QuestionnaireOptions& options = {});

/// One sentence for a report's note naming the excluded survey rows and how to keep them; "" when
/// none was excluded.
std::string describe_exclusions(const Questionnaire& questionnaire);

/// Largest number of scale points accepted (0-100 rating scales); more is a usage error.
inline constexpr long long kMaxScalePoints = 101;

/// Parses `--scale MIN-MAX` (whole numbers, MIN < MAX, at most kMaxScalePoints points, negative
/// bounds allowed: `-3-3`).
std::pair<int, int> parse_scale(std::string_view text);

/// Parses `--labels "Strongly disagree=1,Disagree=2,..."` (CSV quoting allowed for labels that
/// contain commas; each value a whole number). Throws UsageError.
std::vector<LabelEntry> parse_label_map(std::string_view text);

/// The built-in agree/disagree map for a 5- or 7-point scale starting at `scale_min`; empty for
/// other scale lengths. 5 points: Strongly disagree, Disagree (= Somewhat disagree), Neither agree
/// nor disagree (= Neutral), Agree (= Somewhat agree), Strongly agree. 7 points: Strongly disagree,
/// Disagree, Somewhat disagree, Neither agree nor disagree (= Neutral), Somewhat agree, Agree,
/// Strongly agree.
std::vector<LabelEntry> builtin_agree_labels(int scale_min, int scale_max);

}  // namespace feint::io
