// Likert questionnaire loader (formats.md, Questionnaires). See feint/io/questionnaire.hpp.
#include "feint/io/questionnaire.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::io {

namespace detail {
namespace {

/// A record kept in memory: questionnaires are small, and the Qualtrics check needs look-ahead.
struct Record {
  std::uint64_t line = 0;
  std::vector<std::string> fields;
};

bool iequals(std::string_view a, std::string_view b) {
  return to_lower(trim(a)) == to_lower(trim(b));
}

/// Column metadata written by survey platforms, never an item unless named in --items.
constexpr std::array<std::string_view, 23> kPlatformColumns = {
    // Qualtrics
    "startdate", "enddate", "status", "ipaddress", "progress", "duration (in seconds)", "finished",
    "recordeddate", "responseid", "recipientlastname", "recipientfirstname", "recipientemail",
    "externalreference", "externaldatareference", "locationlatitude", "locationlongitude",
    "distributionchannel", "userlanguage", "q_recaptchascore", "q_relevantidduplicate",
    // Google Forms
    "timestamp", "email address", "score"};

bool is_platform_column(std::string_view name) {
  const std::string key = to_lower(trim(name));
  return std::find(kPlatformColumns.begin(), kPlatformColumns.end(), key) != kPlatformColumns.end();
}

std::string scale_text(int lo, int hi) { return fmt::format("{}-{}", lo, hi); }

/// Converts one answer to a scale point, or nullopt when empty (missing).
class ResponseParser {
 public:
  ResponseParser(const QuestionnaireOptions& options, std::string file)
      : min_(options.scale_min), max_(options.scale_max), file_(std::move(file)) {
    if (!options.labels.empty()) {
      labels_ = options.labels;
      label_map_ = "user";
    } else {
      labels_ = builtin_agree_labels(min_, max_);
      if (!labels_.empty()) label_map_ = fmt::format("built-in {}-point agree", max_ - min_ + 1);
    }
    for (const auto& e : labels_) keys_.emplace(to_lower(trim(e.text)), e.value);
  }

  const std::string& label_map() const { return label_map_; }
  std::size_t mapped() const { return mapped_; }

  /// `who` is the context in parentheses, e.g. "participant P07".
  std::optional<int> parse(std::string_view raw, std::uint64_t line, std::string_view column,
                           const std::string& who) {
    const std::string_view text = trim(raw);
    if (text.empty()) return std::nullopt;
    if (const auto it = keys_.find(to_lower(text)); it != keys_.end()) {
      ++mapped_;
      return it->second;
    }
    const auto value = parse_double(text);
    if (!value) {
      std::string expected = fmt::format("expected a whole number {}", scale_text(min_, max_));
      if (!label_map_.empty()) {
        expected += fmt::format(" or a label of the {} map", label_map_);
      } else {
        expected += " (use --labels to map text answers)";
      }
      fail(line, fmt::format("column '{}': '{}' is not a number or a known label ({}); {}", column,
                             text, who, expected));
    }
    if (*value < min_ || *value > max_) {
      fail(line, fmt::format("column '{}': {} is outside the scale {} ({})", column, text,
                             scale_text(min_, max_), who));
    }
    if (*value != std::floor(*value)) {
      fail(line, fmt::format("column '{}': {} is not a whole number on the scale {} ({})", column,
                             text, scale_text(min_, max_), who));
    }
    return static_cast<int>(*value);
  }

  [[noreturn]] void fail(std::uint64_t line, const std::string& what) const {
    throw InvalidData(fmt::format("{}:{}: {}", file_, line, what));
  }

 private:
  int min_;
  int max_;
  std::string file_;
  std::vector<LabelEntry> labels_;
  std::map<std::string, int> keys_;
  std::string label_map_;
  std::size_t mapped_ = 0;
};

// The column spelled exactly `name` (trimmed), else the one equal to it ignoring case; two or more
// equal only ignoring case are ambiguous (never take the first silently).
int find_column(const std::vector<std::string>& header, std::string_view name,
                const std::string& file = {}) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (trim(header[i]) == trim(name)) return static_cast<int>(i);
  }
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (iequals(header[i], name)) found.push_back(i);
  }
  if (found.empty()) return -1;
  if (found.size() == 1) return static_cast<int>(found[0]);
  std::vector<std::string> names;
  for (const auto i : found) names.push_back(fmt::format("'{}' (column {})", header[i], i + 1));
  throw InvalidData(fmt::format("{}:1: columns {} differ only in case and none is exactly '{}': "
                                "ambiguous; name one exactly with the column's option",
                                file, fmt::join(names, " and "), trim(name)));
}

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

/// Respondent index by (participant, condition), in order of first appearance.
class Respondents {
 public:
  explicit Respondents(Questionnaire& q) : q_(q) {}
  /// Returns (index, line of first appearance, inserted).
  std::pair<std::size_t, bool> find_or_add(const std::string& participant,
                                           const std::string& condition, std::uint64_t line) {
    const auto key = std::make_pair(participant, condition);
    if (const auto it = index_.find(key); it != index_.end()) return {it->second, false};
    const std::size_t i = q_.participants.size();
    index_.emplace(key, i);
    first_line_.push_back(line);
    q_.participants.push_back(participant);
    q_.conditions.push_back(condition);
    for (auto& col : q_.responses) col.emplace_back();
    return {i, true};
  }
  std::uint64_t first_line(std::size_t i) const { return first_line_[i]; }

 private:
  Questionnaire& q_;
  std::map<std::pair<std::string, std::string>, std::size_t> index_;
  std::vector<std::uint64_t> first_line_;
};

/// `--items` entries: item name and the column (wide) or item value (long) it comes from.
struct ItemSpec {
  std::string name;
  std::string source;
  bool renamed = false;  // NAME=SOURCE; otherwise the item keeps the file's spelling
};

std::vector<ItemSpec> parse_item_specs(const std::vector<std::string>& items) {
  std::vector<ItemSpec> specs;
  for (const auto& entry : items) {
    ItemSpec s;
    const auto eq = entry.find('=');
    if (eq == std::string::npos) {
      s.name = s.source = std::string(trim(entry));
    } else {
      s.name = std::string(trim(std::string_view(entry).substr(0, eq)));
      s.source = std::string(trim(std::string_view(entry).substr(eq + 1)));
      s.renamed = true;
    }
    if (s.name.empty() || s.source.empty()) {
      throw UsageError(fmt::format("--items '{}': expected ITEM or NAME=COLUMN", entry));
    }
    for (const auto& prev : specs) {
      if (iequals(prev.name, s.name)) {
        throw UsageError(fmt::format("--items: item '{}' is named twice", s.name));
      }
    }
    specs.push_back(std::move(s));
  }
  return specs;
}

/// Qualtrics' Status values that are not a participant's response, as labels and numeric codes.
std::optional<std::string> non_response_status(std::string_view raw) {
  static constexpr std::array<std::pair<std::string_view, int>, 6> kStatus = {{
      {"Survey Preview", 1}, {"Survey Test", 2}, {"Spam", 8}, {"Preview Spam", 9},
      {"Imported Spam", 12}, {"Offline Preview", 17}}};
  const std::string_view t = trim(raw);
  const auto code = parse_integer(t);
  for (const auto& [label, c] : kStatus) {
    if (iequals(t, label) || (code && *code == c)) return std::string(label);
  }
  return std::nullopt;
}

std::string who(const Questionnaire& q, const std::string& participant,
                const std::string& condition) {
  if (q.has_condition) return fmt::format("participant {}, condition {}", participant, condition);
  return fmt::format("participant {}", participant);
}

}  // namespace
}  // namespace detail

std::string_view to_string(QuestionnaireLayout layout) noexcept {
  switch (layout) {
    case QuestionnaireLayout::long_format:
      return "long";
    case QuestionnaireLayout::wide_format:
      return "wide";
    case QuestionnaireLayout::automatic:
      break;
  }
  return "auto";
}

QuestionnaireLayout parse_questionnaire_layout(std::string_view text) {
  const std::string t = to_lower(trim(text));
  if (t == "long") return QuestionnaireLayout::long_format;
  if (t == "wide") return QuestionnaireLayout::wide_format;
  if (t == "auto") return QuestionnaireLayout::automatic;
  throw UsageError(fmt::format("--layout '{}': expected long, wide or auto", text));
}

std::optional<std::size_t> Questionnaire::item_index(std::string_view name) const {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i] == trim(name)) return i;
  }
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (detail::iequals(items[i], name)) return i;
  }
  return std::nullopt;
}

std::vector<std::string> Questionnaire::condition_names() const {
  std::vector<std::string> out;
  for (const auto& c : conditions) {
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
  return out;
}

std::size_t Questionnaire::missing(std::size_t i) const {
  return static_cast<std::size_t>(
      std::count_if(responses[i].begin(), responses[i].end(), [](const auto& r) { return !r; }));
}

std::pair<int, int> parse_scale(std::string_view text) {
  const std::string_view t = trim(text);
  // The separating '-' is the first one after the first character (MIN may be negative).
  const auto dash = t.size() > 1 ? t.find('-', 1) : std::string_view::npos;
  const auto fail = [&]() -> std::pair<int, int> {
    throw UsageError(
        fmt::format("--scale '{}': expected MIN-MAX with whole numbers MIN < MAX, "
                    "e.g. 1-7",
                    text));
  };
  if (dash == std::string_view::npos) return fail();
  const auto lo = parse_integer(t.substr(0, dash));
  const auto hi = parse_integer(t.substr(dash + 1));
  if (!lo || !hi || *lo >= *hi || *lo < -1000000 || *hi > 1000000) return fail();
  if (*hi - *lo + 1 > kMaxScalePoints) {
    throw UsageError(fmt::format("--scale '{}': {} points; a rating scale has at most {}", text,
                                 *hi - *lo + 1, kMaxScalePoints));
  }
  return {static_cast<int>(*lo), static_cast<int>(*hi)};
}

std::vector<LabelEntry> parse_label_map(std::string_view text) {
  std::vector<LabelEntry> out;
  for (const auto& entry : split_csv_line(text, ',')) {
    if (trim(entry).empty()) continue;
    const auto eq = entry.rfind('=');
    if (eq == std::string::npos) {
      throw UsageError(fmt::format("--labels: '{}' is not of the form Text=N", entry));
    }
    const std::string label(trim(std::string_view(entry).substr(0, eq)));
    const auto value = parse_integer(std::string_view(entry).substr(eq + 1));
    if (label.empty() || !value || *value < -1000000 || *value > 1000000) {
      throw UsageError(
          fmt::format("--labels: '{}' is not of the form Text=N with a whole number N", entry));
    }
    for (const auto& e : out) {
      if (to_lower(e.text) == to_lower(label)) {
        throw UsageError(fmt::format("--labels: label '{}' is given twice", label));
      }
    }
    out.push_back({label, static_cast<int>(*value)});
  }
  if (out.empty()) throw UsageError("--labels: no labels given");
  return out;
}

std::vector<LabelEntry> builtin_agree_labels(int scale_min, int scale_max) {
  const long long points = static_cast<long long>(scale_max) - scale_min + 1;
  const int m = scale_min;
  if (points == 5) {
    return {{"Strongly disagree", m},     {"Disagree", m + 1},
            {"Somewhat disagree", m + 1}, {"Neither agree nor disagree", m + 2},
            {"Neutral", m + 2},           {"Agree", m + 3},
            {"Somewhat agree", m + 3},    {"Strongly agree", m + 4}};
  }
  if (points == 7) {
    return {{"Strongly disagree", m},
            {"Disagree", m + 1},
            {"Somewhat disagree", m + 2},
            {"Neither agree nor disagree", m + 3},
            {"Neutral", m + 3},
            {"Somewhat agree", m + 4},
            {"Agree", m + 5},
            {"Strongly agree", m + 6}};
  }
  return {};
}

std::string describe_exclusions(const Questionnaire& q) {
  if (q.excluded.empty()) return {};
  std::size_t unfinished = 0;
  std::string list;
  for (std::size_t i = 0; i < q.excluded.size(); ++i) {
    const auto& e = q.excluded[i];
    if (e.reason.rfind("unfinished", 0) == 0) ++unfinished;
    if (i < 12) {
      list += fmt::format("{}{} ({})", i == 0 ? "" : ", ", e.id, e.reason);
    } else if (i == 12) {
      list += fmt::format(" and {} more", q.excluded.size() - 12);
    }
  }
  const std::size_t previews = q.excluded.size() - unfinished;
  std::string keep;
  if (previews > 0) keep += "--keep-previews";
  if (unfinished > 0) keep += std::string(keep.empty() ? "" : " / ") + "--keep-unfinished";
  return fmt::format("{} response{} of the survey export excluded, not counted as participants "
                     "({} preview/test/spam, {} unfinished): {}; {} keeps them.",
                     q.excluded.size(), q.excluded.size() == 1 ? "" : "s", previews, unfinished,
                     list, keep);
}

namespace detail {
namespace {

// --scale and --labels, checked before the file is opened.
void check_scale_options(const QuestionnaireOptions& options) {
  if (options.scale_min >= options.scale_max ||
      static_cast<long long>(options.scale_max) - options.scale_min + 1 > kMaxScalePoints) {
    throw UsageError(fmt::format("--scale {}-{}: expected MIN < MAX and at most {} points",
                                 options.scale_min, options.scale_max, kMaxScalePoints));
  }
  for (const auto& e : options.labels) {
    if (e.value < options.scale_min || e.value > options.scale_max) {
      throw UsageError(fmt::format("--labels: '{}={}' is outside the scale {}-{}", e.text, e.value,
                                   options.scale_min, options.scale_max));
    }
  }
}

std::vector<Record> read_records(CsvReader& reader) {
  std::vector<Record> records;
  while (reader.next()) {
    Record r;
    r.line = reader.line();
    for (const auto f : reader.fields()) r.fields.emplace_back(f);
    records.push_back(std::move(r));
  }
  return records;
}

// Qualtrics: row 2 is the question text, row 3 holds {"ImportId": ...} cells. Sets q.qualtrics;
// returns the index of the first data record.
std::size_t skip_qualtrics_rows(const std::vector<Record>& records, Questionnaire& q) {
  if (records.size() >= 2) {
    const auto& third = records[1].fields;
    const bool import_ids = std::any_of(third.begin(), third.end(), [](const std::string& f) {
      return trim(f).rfind("{\"ImportId\"", 0) == 0;
    });
    if (import_ids) {
      q.qualtrics = true;
      return 2;
    }
  }
  return 0;
}

// Where a questionnaire file's columns are (-1 = absent).
struct Columns {
  int id = -1;
  int condition = -1;
  int item = -1;      // long layout
  int response = -1;  // long layout
  int status = -1;    // survey exports only: Status, Finished, Progress
  int finished = -1;
  int progress = -1;
};

Columns find_columns(const std::vector<std::string>& header, const QuestionnaireOptions& options,
                     const std::string& file, bool qualtrics) {
  Columns cols;
  cols.id = find_column(header, options.id_column, file);
  if (cols.id < 0 && qualtrics) cols.id = find_column(header, "ResponseId", file);
  if (cols.id < 0) {
    throw InvalidData(fmt::format(
        "{}: no column '{}' (the respondent id); name the study's column with --id-column "
        "(columns: {})",
        file, options.id_column, list_names(header)));
  }
  cols.condition = find_column(header, options.condition_column, file);
  cols.item = find_column(header, options.item_column, file);
  cols.response = find_column(header, options.response_column, file);

  // Survey exports: previews, tests, spam and unfinished responses are not participants.
  const bool survey_export = qualtrics || find_column(header, "ResponseId", file) >= 0;
  cols.status = survey_export ? find_column(header, "Status", file) : -1;
  cols.finished = survey_export ? find_column(header, "Finished", file) : -1;
  cols.progress = survey_export ? find_column(header, "Progress", file) : -1;
  return cols;
}

// One answer of the long layout, kept until the items x respondents table is built.
struct Answer {
  std::size_t respondent;
  std::size_t item;
  std::optional<int> value;
};

// Reads the data records of one file into a Questionnaire, in its layout: the state every step
// shares, held by reference.
class RecordReader {
 public:
  RecordReader(const QuestionnaireOptions& options, const std::string& file,
               const std::vector<std::string>& header, const Columns& cols, Questionnaire& q,
               ResponseParser& parser, Respondents& respondents)
      : options_(options), file_(file), header_(header), cols_(cols), q_(q), parser_(parser),
        respondents_(respondents) {}

  void read_long(const std::vector<Record>& records, std::size_t first,
                 const std::vector<ItemSpec>& item_specs);
  void read_wide(const std::vector<Record>& records, std::size_t first,
                 const std::vector<ItemSpec>& item_specs);

 private:
  bool excluded(const Record& r);
  std::pair<std::string, std::string> read_key(const Record& r);
  std::vector<Answer> collect_long_answers(const std::vector<Record>& records, std::size_t first,
                                           const std::vector<ItemSpec>& item_specs);
  void build_long_table(const std::vector<Answer>& answers);
  void order_items_as_listed(const std::vector<ItemSpec>& item_specs);
  void add_wide_items(const std::vector<ItemSpec>& item_specs, std::vector<std::size_t>& cols);

  const QuestionnaireOptions& options_;
  const std::string& file_;
  const std::vector<std::string>& header_;
  const Columns& cols_;
  Questionnaire& q_;
  ResponseParser& parser_;
  Respondents& respondents_;
};

// A survey-export row that is no participant's response is noted in q.excluded (true), unless the
// options keep it.
bool RecordReader::excluded(const Record& r) {
  std::optional<std::string> reason;
  if (cols_.status >= 0 && !options_.keep_previews) {
    reason = non_response_status(r.fields[static_cast<std::size_t>(cols_.status)]);
  }
  if (!reason && !options_.keep_unfinished && (cols_.finished >= 0 || cols_.progress >= 0)) {
    const std::string_view fin =
        cols_.finished >= 0 ? trim(r.fields[static_cast<std::size_t>(cols_.finished)]) : "";
    const std::string_view prog =
        cols_.progress >= 0 ? trim(r.fields[static_cast<std::size_t>(cols_.progress)]) : "";
    const auto progress = parse_double(prog);
    if (iequals(fin, "false") || fin == "0" || (progress && *progress < 100.0)) {
      std::vector<std::string> parts;
      if (cols_.finished >= 0) parts.push_back(fmt::format("Finished {}", fin));
      if (cols_.progress >= 0) parts.push_back(fmt::format("Progress {}", prog));
      reason = fmt::format("unfinished ({})", list_names(parts));
    }
  }
  if (!reason) return false;
  std::string id = cols_.id >= 0 ? std::string(trim(r.fields[static_cast<std::size_t>(cols_.id)]))
                                 : std::string();
  if (id.empty()) id = fmt::format("line {}", r.line);
  q_.excluded.push_back({static_cast<std::size_t>(r.line), std::move(id), std::move(*reason)});
  return true;
}

// The record's (participant, condition); neither may be empty.
std::pair<std::string, std::string> RecordReader::read_key(const Record& r) {
  const std::string participant(trim(r.fields[static_cast<std::size_t>(cols_.id)]));
  if (participant.empty()) {
    parser_.fail(r.line, fmt::format("column '{}': empty respondent id",
                                     header_[static_cast<std::size_t>(cols_.id)]));
  }
  std::string condition;
  if (cols_.condition >= 0) {
    condition = std::string(trim(r.fields[static_cast<std::size_t>(cols_.condition)]));
    if (condition.empty()) {
      parser_.fail(r.line, fmt::format("column '{}': empty condition (participant {})",
                                       header_[static_cast<std::size_t>(cols_.condition)],
                                       participant));
    }
  }
  return std::make_pair(participant, condition);
}

// The long layout: one row per respondent and item.
void RecordReader::read_long(const std::vector<Record>& records, std::size_t first,
                             const std::vector<ItemSpec>& item_specs) {
  if (cols_.item < 0 || cols_.response < 0) {
    throw InvalidData(fmt::format("{}: the long layout needs columns '{}' and '{}' (columns: {})",
                                  file_, options_.item_column, options_.response_column,
                                  list_names(header_)));
  }
  // Answers are collected as (respondent, item, value) first and the items x respondents table
  // is built once at the end: memory stays linear in the rows (a table grown row by row is
  // items x respondents, quadratic when every row brings a new item and a new respondent).
  std::vector<Answer> answers = collect_long_answers(records, first, item_specs);
  build_long_table(answers);
  answers = {};
  if (!item_specs.empty()) order_items_as_listed(item_specs);
}

std::vector<Answer> RecordReader::collect_long_answers(const std::vector<Record>& records,
                                                       std::size_t first,
                                                       const std::vector<ItemSpec>& item_specs) {
  const auto item_col = static_cast<std::size_t>(cols_.item);
  const auto resp_col = static_cast<std::size_t>(cols_.response);
  // --items selects items (rows of other items are skipped, unread) and sets their order.
  const auto selected = [&](const std::string& item) {
    if (item_specs.empty()) return true;
    return std::any_of(item_specs.begin(), item_specs.end(),
                       [&](const ItemSpec& s) { return iequals(s.source, item); });
  };
  std::vector<Answer> answers;
  std::unordered_map<std::string, std::size_t> item_index;
  // (respondent, item) -> line of the answer, to name both places of a duplicate.
  std::map<std::pair<std::size_t, std::size_t>, std::uint64_t> seen;
  for (std::size_t k = first; k < records.size(); ++k) {
    const Record& r = records[k];
    ++q_.rows_read;
    if (excluded(r)) continue;
    const auto [participant, condition] = read_key(r);
    const std::string item(trim(r.fields[item_col]));
    if (item.empty()) {
      parser_.fail(r.line, fmt::format("column '{}': empty item name (participant {})",
                                       header_[item_col], participant));
    }
    if (!selected(item)) continue;
    const auto [found, added] = item_index.try_emplace(item, q_.items.size());
    if (added) {
      q_.items.push_back(item);
      q_.item_columns.push_back(header_[resp_col]);
    }
    const std::size_t it = found->second;
    const auto [resp, inserted] = respondents_.find_or_add(participant, condition, r.line);
    (void)inserted;
    if (const auto prev = seen.find({resp, it}); prev != seen.end()) {
      parser_.fail(r.line, fmt::format("{} answered item '{}' twice (first at line {})",
                                       who(q_, participant, condition), item, prev->second));
    }
    seen.emplace(std::make_pair(resp, it), r.line);
    answers.push_back({resp, it,
                       parser_.parse(r.fields[resp_col], r.line, header_[resp_col],
                                     who(q_, participant, condition) + ", item " + item)});
  }
  return answers;
}

// q.responses (items x respondents) from the long layout's answers.
void RecordReader::build_long_table(const std::vector<Answer>& answers) {
  // A table that is mostly holes is not a questionnaire read right (typically the wrong item
  // column: free text, timestamps): refuse it rather than allocate items x respondents cells.
  const std::size_t n_items = q_.items.size(), n_resp = q_.participants.size();
  const double cells = static_cast<double>(n_items) * static_cast<double>(n_resp);
  if (cells > std::max(1048576.0, 64.0 * static_cast<double>(answers.size()))) {
    throw InvalidData(fmt::format(
        "{}: {} items and {} respondents but only {} answers (each item answered by {:.1f} "
        "respondents on average): is the item column right? (--item-column '{}', "
        "--response-column '{}', --layout)",
        file_, n_items, n_resp, answers.size(),
        static_cast<double>(answers.size()) / static_cast<double>(n_items),
        options_.item_column, options_.response_column));
  }
  q_.responses.assign(n_items, std::vector<std::optional<int>>(n_resp));
  for (const auto& ans : answers) q_.responses[ans.item][ans.respondent] = ans.value;
}

// Reorders, renames (and checks) the long layout's items as --items lists them.
void RecordReader::order_items_as_listed(const std::vector<ItemSpec>& item_specs) {
  std::vector<std::string> items, item_columns;
  std::vector<std::vector<std::optional<int>>> responses;
  std::vector<bool> taken(q_.items.size(), false);
  for (const auto& spec : item_specs) {
    const auto i = q_.item_index(spec.source);
    if (!i) {
      throw UsageError(fmt::format("--items: no item '{}' in {} (items: {})", spec.source, file_,
                                   list_names(q_.items)));
    }
    if (taken[*i]) {
      throw UsageError(fmt::format("--items: item '{}' is named twice", spec.source));
    }
    taken[*i] = true;
    items.push_back(spec.renamed ? spec.name : q_.items[*i]);
    item_columns.push_back(spec.renamed ? q_.items[*i] : q_.item_columns[*i]);
    responses.push_back(std::move(q_.responses[*i]));
  }
  q_.items = std::move(items);
  q_.item_columns = std::move(item_columns);
  q_.responses = std::move(responses);
}

// The wide layout: one row per respondent, one column per item.
void RecordReader::read_wide(const std::vector<Record>& records, std::size_t first,
                             const std::vector<ItemSpec>& item_specs) {
  std::vector<std::size_t> cols;
  add_wide_items(item_specs, cols);
  for (std::size_t k = first; k < records.size(); ++k) {
    const Record& r = records[k];
    ++q_.rows_read;
    if (excluded(r)) continue;
    const auto [participant, condition] = read_key(r);
    const auto [resp, inserted] = respondents_.find_or_add(participant, condition, r.line);
    if (!inserted) {
      parser_.fail(r.line, fmt::format("{} has a second row (first at line {}); the wide layout "
                                       "has one row per respondent",
                                       who(q_, participant, condition),
                                       respondents_.first_line(resp)));
    }
    for (std::size_t j = 0; j < cols.size(); ++j) {
      q_.responses[j][resp] = parser_.parse(r.fields[cols[j]], r.line, header_[cols[j]],
                                            who(q_, participant, condition));
    }
  }
}

// The wide layout's item columns (those --items names, else every column that is not the id, the
// condition or survey-platform metadata) into `cols`, and their items into q.
void RecordReader::add_wide_items(const std::vector<ItemSpec>& item_specs,
                                  std::vector<std::size_t>& cols) {
  const int id_col = cols_.id, cond_col = cols_.condition;
  std::vector<std::string> names;  // item names (renamed by --items NAME=COLUMN)
  if (!item_specs.empty()) {
    for (const auto& spec : item_specs) {
      const std::string& name = spec.source;
      const int c = find_column(header_, name, file_);
      if (c < 0) {
        throw UsageError(fmt::format("--items: no column '{}' in {} (columns: {})", name, file_,
                                     list_names(header_)));
      }
      if (c == id_col || c == cond_col) {
        throw UsageError(fmt::format("--items: '{}' is the id or condition column", name));
      }
      if (std::find(cols.begin(), cols.end(), static_cast<std::size_t>(c)) != cols.end()) {
        throw UsageError(fmt::format("--items: column '{}' is named twice", name));
      }
      cols.push_back(static_cast<std::size_t>(c));
      names.push_back(spec.renamed ? spec.name : std::string(trim(header_[c])));
    }
  } else {
    for (std::size_t c = 0; c < header_.size(); ++c) {
      if (static_cast<int>(c) == id_col || static_cast<int>(c) == cond_col) continue;
      if (is_platform_column(header_[c])) continue;
      if (trim(header_[c]).empty()) continue;
      cols.push_back(c);
      names.emplace_back(trim(header_[c]));
    }
  }
  if (cols.empty()) {
    throw InvalidData(fmt::format("{}: no item columns (columns: {})", file_, list_names(header_)));
  }
  for (std::size_t j = 0; j < cols.size(); ++j) {
    for (const auto& prev : q_.items) {
      if (iequals(prev, names[j])) {
        throw InvalidData(
            fmt::format("{}: item column '{}' appears twice in the header", file_, prev));
      }
    }
    q_.items.push_back(names[j]);
    q_.item_columns.push_back(header_[cols[j]]);
    q_.responses.emplace_back();
  }
}

// Reverse coding (--reverse), before anything else sees the data.
void reverse_code(Questionnaire& q, const std::vector<std::string>& reverse) {
  q.reversed.assign(q.items.size(), false);
  for (const auto& name : reverse) {
    const auto i = q.item_index(name);
    if (!i) {
      throw UsageError(
          fmt::format("--reverse: no item '{}' (items: {})", name, list_names(q.items)));
    }
    if (q.reversed[*i]) throw UsageError(fmt::format("--reverse: item '{}' is named twice", name));
    q.reversed[*i] = true;
    for (auto& x : q.responses[*i]) {
      if (x) x = q.scale_min + q.scale_max - *x;
    }
  }
}

}  // namespace
}  // namespace detail

Questionnaire load_questionnaire(const std::string& path, const QuestionnaireOptions& options) {
  detail::check_scale_options(options);

  CsvOptions csv;
  csv.delimiter = options.delimiter;
  CsvReader reader(path, csv);
  const std::string file = path == "-" ? "standard input" : path;
  const std::vector<std::string> header = reader.header();
  const std::vector<detail::Record> records = detail::read_records(reader);

  Questionnaire q;
  q.source = path;
  q.scale_min = options.scale_min;
  q.scale_max = options.scale_max;
  const std::size_t first = detail::skip_qualtrics_rows(records, q);
  const detail::Columns cols = detail::find_columns(header, options, file, q.qualtrics);
  q.has_condition = cols.condition >= 0;
  const std::vector<detail::ItemSpec> item_specs = detail::parse_item_specs(options.items);

  q.layout = options.layout;
  if (q.layout == QuestionnaireLayout::automatic) {
    q.layout = cols.item >= 0 && cols.response >= 0 ? QuestionnaireLayout::long_format
                                                    : QuestionnaireLayout::wide_format;
  }

  detail::ResponseParser parser(options, file);
  detail::Respondents respondents(q);
  detail::RecordReader rows(options, file, header, cols, q, parser, respondents);
  if (q.layout == QuestionnaireLayout::long_format) {
    rows.read_long(records, first, item_specs);
  } else {
    rows.read_wide(records, first, item_specs);
  }

  if (q.participants.empty()) {
    if (!q.excluded.empty()) {
      throw InvalidData(fmt::format("{}: no responses: {}", file, describe_exclusions(q)));
    }
    throw InvalidData(fmt::format("{}: no responses (a header but no data rows)", file));
  }
  q.text_answers_mapped = parser.mapped();
  if (q.text_answers_mapped > 0) q.label_map = parser.label_map();
  detail::reverse_code(q, options.reverse);
  return q;
}

}  // namespace feint::io
