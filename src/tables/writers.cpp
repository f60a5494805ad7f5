#include "feint/tables/writers.hpp"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::tables {

// ---------------------------------------------------------------------------------------------
// Tidy records

Cell Cell::num(std::optional<double> v) {
  if (!v || std::isnan(*v)) return {};
  if (std::isinf(*v)) return {Kind::text, *v > 0 ? "Inf" : "-Inf"};  // R's spelling; not JSON
  return {Kind::number, io::format_double(*v)};
}

namespace {
Cell text_or_none(const std::string& s) { return s.empty() ? Cell::none() : Cell::str(s); }
}  // namespace

Cell tidy_cell(const TidyRow& row, std::string_view c) {
  const stats::TestResult& r = row.result;
  if (c == "metric") return text_or_none(row.metric);
  if (c == "iteration") return row.iteration ? Cell::integer(*row.iteration) : Cell::none();
  if (c == "test") return text_or_none(r.test);
  if (c == "method") return text_or_none(r.method);
  if (c == "alternative") {
    return r.test.empty() ? Cell::none() : Cell::str(std::string(stats::to_string(r.alternative)));
  }
  if (c == "mu") return Cell::num(r.mu);
  if (c == "group1") return text_or_none(row.group1);
  if (c == "group2") return text_or_none(row.group2);
  if (c == "n1") return Cell::integer(static_cast<long long>(r.n1));
  if (c == "n2") {
    return (!row.group2.empty() || r.n2 > 0) ? Cell::integer(static_cast<long long>(r.n2))
                                             : Cell::none();
  }
  if (c == "mean1") return Cell::num(r.mean1);
  if (c == "mean2") return Cell::num(r.mean2);
  if (c == "sd1") return Cell::num(r.sd1);
  if (c == "sd2") return Cell::num(r.sd2);
  if (c == "estimate") return Cell::num(r.estimate);
  if (c == "conf_low") return Cell::num(r.conf_low);
  if (c == "conf_high") return Cell::num(r.conf_high);
  if (c == "statistic") return Cell::num(r.statistic);
  if (c == "df") return Cell::num(r.df);
  if (c == "p_value") return Cell::num(r.p_value);
  if (c == "p_adjusted") return Cell::num(r.p_adjusted);
  if (c == "cohen_d") return Cell::num(r.cohen_d);
  if (c == "hedges_g") return Cell::num(r.hedges_g);
  if (c == "cohen_d_low") return Cell::num(r.cohen_d_low);
  if (c == "cohen_d_high") return Cell::num(r.cohen_d_high);
  if (c == "hedges_g_low") return Cell::num(r.hedges_g_low);
  if (c == "hedges_g_high") return Cell::num(r.hedges_g_high);
  if (c == "bf10") return Cell::num(r.bf10);
  if (c == "bf01") return Cell::num(r.bf01);
  if (c == "rank_biserial_low") return Cell::num(r.rank_biserial_low);
  if (c == "rank_biserial_high") return Cell::num(r.rank_biserial_high);
  if (c == "label") return text_or_none(row.label);
  if (c == "note") return text_or_none(r.note);
  if (c == "median1") return Cell::num(r.median1);
  if (c == "median2") return Cell::num(r.median2);
  if (c == "iqr1") return Cell::num(r.iqr1);
  if (c == "iqr2") return Cell::num(r.iqr2);
  if (c == "rank_biserial") return Cell::num(r.rank_biserial);
  if (c == "exact") return Cell::flag(r.exact);
  if (c == "cronbach_alpha") return Cell::num(row.cronbach_alpha);
  if (c == "apa") return text_or_none(row.apa);
  throw std::invalid_argument(fmt::format("tidy_cell: unknown column '{}'", c));
}

std::vector<Record> tidy_records(std::span<const TidyRow> rows,
                                 std::span<const std::string_view> columns) {
  std::vector<Record> out;
  out.reserve(rows.size());
  for (const auto& row : rows) {
    Record rec;
    rec.reserve(columns.size());
    for (auto c : columns) rec.push_back(tidy_cell(row, c));
    out.push_back(std::move(rec));
  }
  return out;
}

std::vector<std::string_view> table_columns(bool apa) {
  std::vector<std::string_view> cols(kTableColumns.begin(), kTableColumns.end());
  if (apa) cols.push_back("apa");
  return cols;
}

std::vector<std::string_view> likert_columns(bool apa) {
  std::vector<std::string_view> cols(kTableColumns.begin(), kTableColumns.end());
  cols.insert(cols.end(), kLikertExtraColumns.begin(), kLikertExtraColumns.end());
  if (apa) cols.push_back("apa");
  return cols;
}

std::string write_csv(std::span<const std::string_view> columns, std::span<const Record> records) {
  std::string out;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) out += ',';
    out += io::csv_escape(columns[i]);
  }
  out += '\n';
  for (const auto& rec : records) {
    for (std::size_t i = 0; i < rec.size(); ++i) {
      if (i > 0) out += ',';
      out += io::csv_escape(rec[i].text);
    }
    out += '\n';
  }
  return out;
}

std::string write_json(std::span<const std::string_view> columns, std::span<const Record> records) {
  if (records.empty()) return "[]\n";
  std::string out = "[\n";
  for (std::size_t r = 0; r < records.size(); ++r) {
    out += "  {";
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (i > 0) out += ", ";
      out += io::json_quote(columns[i]);
      out += ": ";
      const Cell empty;
      const Cell& cell = i < records[r].size() ? records[r][i] : empty;
      switch (cell.kind) {
        case Cell::Kind::empty: out += "null"; break;
        case Cell::Kind::text: out += io::json_quote(cell.text); break;
        case Cell::Kind::number:
        case Cell::Kind::boolean: out += cell.text; break;
      }
    }
    out += r + 1 < records.size() ? "},\n" : "}\n";
  }
  out += "]\n";
  return out;
}

std::string tidy_csv(std::span<const TidyRow> rows, std::span<const std::string_view> columns) {
  const auto records = tidy_records(rows, columns);
  return write_csv(columns, records);
}

std::string tidy_json(std::span<const TidyRow> rows, std::span<const std::string_view> columns) {
  const auto records = tidy_records(rows, columns);
  return write_json(columns, records);
}

std::string latex_escape(std::string_view text) {
  std::string out;
  bool open_quote = false;  // "x" -> ``x'' (a straight quote prints as a closing one in OT1)
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    const std::string_view rest = text.substr(i);
    auto starts = [&](std::string_view s) { return rest.substr(0, s.size()) == s; };
    if (starts("\u2248")) { out += "\\ensuremath{\\approx}"; i += 2; continue; }
    if (starts("\u00b1")) { out += "\\ensuremath{\\pm}"; i += 1; continue; }
    if (starts("\u00d7")) { out += "\\ensuremath{\\times}"; i += 1; continue; }
    if (starts("\u03b1")) { out += "\\ensuremath{\\alpha}"; i += 1; continue; }
    if (starts("\u03b4")) { out += "\\ensuremath{\\delta}"; i += 1; continue; }
    if (starts("\u03c7")) { out += "\\ensuremath{\\chi}"; i += 1; continue; }
    if (starts("\u03b7")) { out += "\\ensuremath{\\eta}"; i += 1; continue; }
    if (starts("\u00b2")) { out += "\\textsuperscript{2}"; i += 1; continue; }
    if (starts("\u2081\u2080")) { out += "\\textsubscript{10}"; i += 5; continue; }  // BF10
    if (starts("\u2080\u2081")) { out += "\\textsubscript{01}"; i += 5; continue; }  // BF01
    if (starts("\u2013")) { out += "--"; i += 2; continue; }
    if (starts("\u2014")) { out += "---"; i += 2; continue; }
    if (starts("\u2265")) { out += "\\ensuremath{\\geq}"; i += 2; continue; }
    if (starts("\u2264")) { out += "\\ensuremath{\\leq}"; i += 2; continue; }
    switch (ch) {
      case '"':
        out += open_quote ? "''" : "``";
        open_quote = !open_quote;
        break;
      case '&': out += "\\&"; break;
      case '%': out += "\\%"; break;
      case '$': out += "\\$"; break;
      case '#': out += "\\#"; break;
      case '_': out += "\\_"; break;
      case '{': out += "\\{"; break;
      case '}': out += "\\}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '\\': out += "\\textbackslash{}"; break;
      case '<': out += "\\textless{}"; break;  // OT1 would print an inverted "!"
      case '>': out += "\\textgreater{}"; break;
      default: out += ch;
    }
  }
  return out;
}

std::size_t display_width(std::string_view utf8) noexcept {
  std::size_t w = 0;
  for (const char ch : utf8) {
    if ((static_cast<unsigned char>(ch) & 0xC0) != 0x80) ++w;
  }
  return w;
}

// ---------------------------------------------------------------------------------------------
// Aligned tables

namespace {

std::string pad(std::string_view s, std::size_t width, bool right) {
  const std::size_t w = display_width(s);
  const std::string fill(width > w ? width - w : 0, ' ');
  return right ? fill + std::string(s) : std::string(s) + fill;
}

std::string rstrip(std::string s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// Greedy word wrap of a paragraph to `width` columns.
std::string wrap(std::string_view text, std::size_t width) {
  std::string out, line;
  std::size_t i = 0;
  while (i < text.size()) {
    const auto j = text.find(' ', i);
    const std::string_view word = text.substr(i, j == std::string_view::npos ? j : j - i);
    if (!line.empty() && display_width(line) + 1 + display_width(word) > width) {
      out += line + '\n';
      line.clear();
    }
    if (!line.empty()) line += ' ';
    line += word;
    if (j == std::string_view::npos) break;
    i = j + 1;
  }
  if (!line.empty()) out += line + '\n';
  return out;
}

std::size_t column_count(const TextTable& t) {
  std::size_t n = t.header.size();
  for (const auto& r : t.rows) {
    if (!r.section) n = std::max(n, r.cells.size());
  }
  return n;
}

std::string cell_at(const std::vector<std::string>& cells, std::size_t i) {
  return i < cells.size() ? cells[i] : std::string();
}

bool right_at(const TextTable& t, std::size_t i) {
  return i < t.right_align.size() && t.right_align[i];
}

std::string render_text(const TextTable& t) {
  const std::size_t n = column_count(t);
  const std::string sep = "  ";
  std::vector<std::size_t> width(n, 0);
  for (std::size_t i = 0; i < n; ++i) width[i] = display_width(cell_at(t.header, i));
  for (const auto& r : t.rows) {
    if (r.section) continue;
    for (std::size_t i = 0; i < n; ++i) width[i] = std::max(width[i], display_width(cell_at(r.cells, i)));
  }
  // A group title wider than its columns widens the last column it spans.
  for (const auto& g : t.groups) {
    if (g.count == 0 || g.first + g.count > n) continue;
    std::size_t span = 0;
    for (std::size_t i = g.first; i < g.first + g.count; ++i) span += width[i];
    span += sep.size() * (g.count - 1);
    const std::size_t need = display_width(g.title);
    if (need > span) width[g.first + g.count - 1] += need - span;
  }
  std::string out;
  if (!t.caption.empty()) out += t.caption + "\n\n";
  if (!t.groups.empty()) {
    std::string titles, rules;
    std::size_t col = 0;
    for (const auto& g : t.groups) {
      if (g.count == 0 || g.first + g.count > n || g.first < col) continue;
      for (; col < g.first; ++col) {
        titles += std::string(width[col], ' ') + sep;
        rules += std::string(width[col], ' ') + sep;
      }
      std::size_t span = sep.size() * (g.count - 1);
      for (std::size_t i = g.first; i < g.first + g.count; ++i) span += width[i];
      titles += pad(g.title, span, false) + sep;
      rules += std::string(span, '-') + sep;
      col = g.first + g.count;
    }
    out += rstrip(titles) + '\n' + rstrip(rules) + '\n';
  }
  std::string line;
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    line += pad(cell_at(t.header, i), width[i], right_at(t, i)) + (i + 1 < n ? sep : "");
    total += width[i] + (i + 1 < n ? sep.size() : 0);
  }
  out += rstrip(line) + '\n' + std::string(total, '-') + '\n';
  bool first = true;
  for (const auto& r : t.rows) {
    if (r.section) {
      if (!first) out += '\n';
      out += cell_at(r.cells, 0) + '\n';
    } else {
      line.clear();
      for (std::size_t i = 0; i < n; ++i) {
        line += pad(cell_at(r.cells, i), width[i], right_at(t, i)) + (i + 1 < n ? sep : "");
      }
      out += rstrip(line) + '\n';
    }
    first = false;
  }
  out += std::string(total, '-') + '\n';
  for (const auto& note : t.notes) out += '\n' + wrap(note, std::max<std::size_t>(total, 72));
  return out;
}

std::string md_cell(std::string_view s) {
  std::string out;
  for (const char ch : s) {
    if (ch == '|') out += "\\|";
    else out += ch;
  }
  return out;
}

std::string render_markdown(const TextTable& t) {
  const std::size_t n = column_count(t);
  std::string out;
  if (!t.caption.empty()) out += "**" + md_cell(t.caption) + "**\n\n";
  auto row_line = [&](const std::vector<std::string>& cells, bool bold) {
    std::string l = "|";
    for (std::size_t i = 0; i < n; ++i) {
      const std::string c = md_cell(cell_at(cells, i));
      l += ' ' + ((bold && !c.empty()) ? "**" + c + "**" : c) + " |";
    }
    return l + '\n';
  };
  std::string align = "|";
  for (std::size_t i = 0; i < n; ++i) align += right_at(t, i) ? "---:|" : "---|";
  align += '\n';
  if (!t.groups.empty()) {
    std::vector<std::string> g(n);
    for (const auto& grp : t.groups) {
      if (grp.first < n) g[grp.first] = grp.title;
    }
    out += row_line(g, true) + align + row_line(t.header, true);
  } else {
    out += row_line(t.header, false) + align;
  }
  for (const auto& r : t.rows) {
    if (r.section) {
      out += row_line({cell_at(r.cells, 0)}, true);
    } else {
      out += row_line(r.cells, false);
    }
  }
  for (std::size_t i = 0; i < t.notes.size(); ++i) {
    out += '\n' + std::string(i == 0 ? "*Note.* " : "") + t.notes[i] + '\n';
  }
  return out;
}

std::string render_latex(const TextTable& t) {
  const std::size_t n = column_count(t);
  // table* floats only to the top of a page or to a float page: [tp], not [htbp] (h and b are not
  // available to two-column floats).
  const std::string env = t.latex_wide ? "table*" : "table";
  std::string out = "% Needs \\usepackage{booktabs} and \\usepackage{graphicx} in the preamble.\n";
  out += "\\begin{" + env + "}" + (t.latex_wide ? "[tp]" : "[htbp]") + "\n  \\centering\n";
  if (!t.caption.empty()) out += "  \\caption{" + latex_escape(t.caption) + "}\n";
  if (!t.latex_label.empty()) out += "  \\label{" + t.latex_label + "}\n";
  std::string spec;
  for (std::size_t i = 0; i < n; ++i) spec += right_at(t, i) ? 'r' : 'l';
  // Wide tables (Likert with three test blocks, two-sample Table 1) shrink to the line width, and
  // long ones (Table 1 of several conditions x 20 iterations) to 60% of the text height, so the
  // float and its note fit on a page; smaller ones keep their natural size.
  out += "  \\resizebox*{!}{\\ifdim\\totalheight>0.6\\textheight 0.6\\textheight\\else"
         "\\totalheight\\fi}{%\n";
  out += "  \\resizebox{\\ifdim\\width>\\linewidth\\linewidth\\else\\width\\fi}{!}{%\n";
  out += "  \\begin{tabular}{" + spec + "}\n    \\toprule\n";
  if (!t.groups.empty()) {
    std::string l = "   ";
    std::string rules = "   ";
    std::size_t col = 0;
    bool any = false;
    for (const auto& g : t.groups) {
      if (g.count == 0 || g.first + g.count > n || g.first < col) continue;
      for (; col < g.first; ++col) l += col == 0 ? " " : " & ";
      l += std::string(col == 0 ? " " : " & ") + "\\multicolumn{" + std::to_string(g.count) +
           "}{c}{" + latex_escape(g.title) + "}";
      rules += fmt::format(" \\cmidrule(lr){{{}-{}}}", g.first + 1, g.first + g.count);
      col = g.first + g.count;
      any = true;
    }
    for (; col < n; ++col) l += " &";
    if (any) out += l + " \\\\\n" + rules + "\n";
  }
  std::string h = "   ";
  for (std::size_t i = 0; i < n; ++i) h += (i == 0 ? " " : " & ") + latex_escape(cell_at(t.header, i));
  out += h + " \\\\\n    \\midrule\n";
  bool first = true;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    if (row.section) {
      if (!first) out += "    \\addlinespace\n";
      out += "    \\multicolumn{" + std::to_string(n) + "}{l}{\\textit{" +
             latex_escape(cell_at(row.cells, 0)) + "}} \\\\\n";
    } else {
      std::string l = "   ";
      for (std::size_t i = 0; i < n; ++i) {
        const bool verbatim = r < t.latex_cells.size() && i < t.latex_cells[r].size() &&
                              !t.latex_cells[r][i].empty();
        l += (i == 0 ? " " : " & ") +
             (verbatim ? t.latex_cells[r][i] : latex_escape(cell_at(row.cells, i)));
      }
      out += l + " \\\\\n";
    }
    first = false;
  }
  out += "    \\bottomrule\n  \\end{tabular}}}\n";
  if (!t.notes.empty()) {
    // Flush left, ragged right (as APA table notes): justified notes in a narrow column stretch
    // around long words such as afex::aov_ez and LaTeX warns of an underfull box.
    out +=
        "  \\par\\smallskip\n  \\begin{minipage}{\\linewidth}\n    \\footnotesize\\raggedright\n";
    for (std::size_t i = 0; i < t.notes.size(); ++i) {
      out += std::string("    ") + (i == 0 ? "\\textit{Note.} " : "\\par ") +
             latex_escape(t.notes[i]) + "\n";
    }
    out += "  \\end{minipage}\n";
  }
  out += "\\end{" + env + "}\n";
  return out;
}

}  // namespace

void validate_latex_label(std::string_view label) {
  const bool ok = !label.empty() && std::all_of(label.begin(), label.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == ':' || c == '-' || c == '_' ||
           c == '.' || c == '/' || c == '+';
  });
  if (!ok) {
    throw UsageError(fmt::format("--label '{}': use letters, digits and : - _ . / + only (e.g. "
                                 "tab:confusion)",
                                 label));
  }
}

std::string latex_label_part(std::string_view text) {
  std::string out;
  bool dash = false;
  for (const char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
      if (dash && !out.empty()) out += '-';
      dash = false;
      out += c;
    } else {
      dash = true;
    }
  }
  return out.empty() ? "x" : out;
}

void apply_presentation(TextTable& t, const TablePresentation& p, std::string_view default_label) {
  t.latex_label = p.label.empty() ? std::string(default_label) : p.label;
  if (!p.caption.empty()) t.caption = p.caption;
  t.latex_wide = p.wide;
}

std::string render_table(const TextTable& table, OutputFormat format) {
  switch (format) {
    case OutputFormat::text: return render_text(table);
    case OutputFormat::markdown: return render_markdown(table);
    case OutputFormat::latex: return render_latex(table);
    case OutputFormat::csv:
    case OutputFormat::json: break;
  }
  throw std::invalid_argument("render_table: csv/json are tidy formats (write_csv/write_json)");
}

}  // namespace feint::tables
