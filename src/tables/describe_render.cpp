// `feint describe`'s table as text, Markdown, LaTeX, CSV and JSON (see feint/tables/describe.hpp);
// its numbers are computed in describe.cpp.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <optional>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/stats/exact_decimal.hpp"
#include "feint/tables/describe.hpp"

namespace feint::tables {

std::string format_for_print(double value, int digits) {
  if (!std::isfinite(value)) return io::format_double(value);
  // signif(value, digits) as R rounds for print, then the shortest text of that double.
  const std::string rounded = fmt::format("{:.{}e}", value, digits - 1);
  const double r = std::strtod(rounded.c_str(), nullptr);
  return fmt::format("{}", r == 0 ? 0.0 : r);
}

std::vector<Record> describe_records(const DescribeTable& t) {
  std::vector<Record> out;
  for (std::size_t g = 0; g < t.groups.size(); ++g) {
    const auto& d = t.descriptions[g];
    out.push_back({Cell::str(t.variable), t.by.empty() ? Cell::none() : Cell::str(t.groups[g]),
                   Cell::integer(static_cast<long long>(d.n)), Cell::num(d.mean), Cell::num(d.sd),
                   Cell::num(d.se), Cell::num(d.min), Cell::num(d.q1), Cell::num(d.median),
                   Cell::num(d.q3), Cell::num(d.max), Cell::num(d.conf_low),
                   Cell::num(d.conf_high), Cell::num(d.autocorr_lag1)});
  }
  return out;
}

std::string render_describe(const DescribeTable& t, OutputFormat format) {
  const auto records = describe_records(t);
  const std::vector<std::string_view> columns(kDescribeColumns.begin(), kDescribeColumns.end());
  if (format == OutputFormat::csv) return write_csv(columns, records);
  if (format == OutputFormat::json) return write_json(columns, records);
  TextTable tt;
  tt.caption = t.by.empty() ? fmt::format("Descriptive statistics of {}", t.variable)
                            : fmt::format("Descriptive statistics of {} by {}", t.variable, t.by);
  tt.latex_label = "tab:feint-describe";
  for (auto c : columns) {
    tt.header.emplace_back(c);
    tt.right_align.push_back(c != "variable" && c != "group");
  }
  // For print: statistics rounded to kPrintDigits significant digits (a reader compares them with
  // a paper's); CSV and JSON above keep every digit (the shortest round-trip text).
  for (const auto& rec : records) {
    TextTable::Row row;
    for (std::size_t c = 0; c < rec.size(); ++c) {
      const auto& cell = rec[c];
      const bool statistic = columns[c] != "variable" && columns[c] != "group" && columns[c] != "n";
      const auto v = statistic && cell.kind == Cell::Kind::number
                         ? io::parse_double(cell.text) : std::optional<double>();
      row.cells.push_back(v ? format_for_print(*v, kPrintDigits) : cell.text);
    }
    tt.rows.push_back(std::move(row));
  }
  tt.notes.push_back(fmt::format(
      "sd with n - 1; se = sd / sqrt(n); quartiles as R's quantile(type = 7); conf_low/conf_high: "
      "{}% t confidence interval of the mean; autocorr_lag1: lag-1 autocorrelation in file order "
      "(NIST's r1). Numbers rounded to {} significant digits for print; --format csv or json gives "
      "them in full precision.",
      io::format_double(t.conf_level * 100), kPrintDigits));
  for (std::size_t g = 0; g < t.groups.size(); ++g) {
    const std::string who = t.by.empty() ? t.variable : fmt::format("{} = {}", t.by, t.groups[g]);
    if (g < t.missing.size() && t.missing[g] > 0) {
      tt.notes.push_back(fmt::format("{}: {} empty cell{} excluded as missing.", who, t.missing[g],
                                     t.missing[g] == 1 ? "" : "s"));
    }
    if (!t.descriptions[g].note.empty()) {
      tt.notes.push_back(fmt::format("{}: {}.", who, t.descriptions[g].note));
    }
  }
  tt.notes.push_back(fmt::format("Source: {}.", t.source));
  return render_table(tt, format);
}

}  // namespace feint::tables
