// The self-contained HTML report page (see html.hpp).
#include "feint/plot/html.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <sstream>

#include "feint/io/html_escape.hpp"

namespace feint::plot {

using io::html_escape;

namespace {

void replace_all(std::string& s, std::string_view from, std::string_view to) {
  std::size_t pos = 0;
  while ((pos = s.find(from, pos)) != std::string::npos) {
    s.replace(pos, from.size(), to);
    pos += to.size();
  }
}

// **bold** and *emphasis* in already-escaped text.
std::string inline_markup(std::string text) {
  for (const auto& [mark, open, close] :
       {std::tuple{std::string_view("**"), "<strong>", "</strong>"},
        std::tuple{std::string_view("*"), "<em>", "</em>"}}) {
    std::string out;
    std::size_t pos = 0;
    while (true) {
      const std::size_t a = text.find(mark, pos);
      if (a == std::string::npos) break;
      const std::size_t b = text.find(mark, a + mark.size());
      if (b == std::string::npos || b == a + mark.size()) break;
      out += text.substr(pos, a - pos);
      out += open;
      out += text.substr(a + mark.size(), b - a - mark.size());
      out += close;
      pos = b + mark.size();
    }
    out += text.substr(pos);
    text = std::move(out);
  }
  return text;
}

std::vector<std::string> split_row(std::string_view line) {
  // "| a | b |" -> {"a", "b"}; feint's writers never put a pipe inside a cell.
  std::vector<std::string> cells;
  std::string_view s = line;
  if (!s.empty() && s.front() == '|') s.remove_prefix(1);
  if (!s.empty() && s.back() == '|') s.remove_suffix(1);
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = s.find('|', start);
    std::string_view cell = s.substr(start, bar == std::string_view::npos ? s.npos : bar - start);
    while (!cell.empty() && cell.front() == ' ') cell.remove_prefix(1);
    while (!cell.empty() && cell.back() == ' ') cell.remove_suffix(1);
    cells.emplace_back(cell);
    if (bar == std::string_view::npos) break;
    start = bar + 1;
  }
  return cells;
}

bool is_separator(const std::vector<std::string>& cells) {
  for (const auto& c : cells) {
    if (c.empty() || c.find_first_not_of(":-") != std::string::npos) return false;
  }
  return !cells.empty();
}

std::string table_html(const std::vector<std::string>& lines) {
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> right;
  std::size_t header_rows = 0;
  for (const auto& l : lines) {
    auto cells = split_row(l);
    if (is_separator(cells)) {
      header_rows = rows.size();
      for (const auto& c : cells) right.push_back(c.back() == ':' && c.front() != ':');
      continue;
    }
    rows.push_back(std::move(cells));
  }
  // The row under the separator is a header too when every filled cell is bold (the column
  // names under a row of column groups), unless it is a section row (only its first cell).
  if (header_rows < rows.size()) {
    const auto& row = rows[header_rows];
    std::size_t filled = 0;
    bool bold = true;
    for (const auto& c : row) {
      if (c.empty()) continue;
      ++filled;
      bold = bold && c.rfind("**", 0) == 0;
    }
    if (bold && filled > 1) ++header_rows;
  }
  std::ostringstream o;
  o << "<div class=\"table\"><table>\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const bool head = r < header_rows;
    if (r == 0 && head) o << "<thead>\n";
    if (r == header_rows) o << (r == 0 ? "<tbody>\n" : "</thead>\n<tbody>\n");
    // A section row: only its first cell is filled and bold ("**Condition: adaptive**").
    bool section = !head && rows[r].size() > 1 && rows[r][0].rfind("**", 0) == 0;
    for (std::size_t c = 1; section && c < rows[r].size(); ++c) section = rows[r][c].empty();
    if (section) {
      o << "<tr class=\"section\"><th colspan=\"" << rows[r].size() << "\">"
        << inline_markup(html_escape(rows[r][0])) << "</th></tr>\n";
      continue;
    }
    o << "<tr>";
    // Header groups: a cell followed by empty ones spans them.
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      std::size_t span = 1;
      if (head && !rows[r][c].empty()) {
        while (c + span < rows[r].size() && rows[r][c + span].empty() && r + 1 < header_rows)
          ++span;
      }
      const char* tag = head ? "th" : "td";
      o << '<' << tag;
      if (span > 1) o << " colspan=\"" << span << "\"";
      if (c < right.size() && right[c] && span == 1) o << " class=\"num\"";
      o << '>' << inline_markup(html_escape(rows[r][c])) << "</" << tag << '>';
      c += span - 1;
    }
    o << "</tr>\n";
  }
  o << (header_rows == rows.size() ? "</thead>\n" : "</tbody>\n") << "</table></div>\n";
  return o.str();
}

constexpr std::string_view kCss = R"css(
:root { color-scheme: light; }
* { box-sizing: border-box; }
body { margin: 0; background: #fff; color: #1a1a1a;
  font: 15px/1.5 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", "Liberation Sans", Arial, sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 32px 48px; }
header h1 { font-size: 26px; margin: 8px 0 2px; }
header p.subtitle { margin: 0 0 12px; color: #555; }
nav { border-top: 1px solid #ddd; border-bottom: 1px solid #ddd; padding: 6px 0; margin-bottom: 8px; font-size: 14px;
  display: flex; flex-wrap: wrap; gap: 2px 14px; }
nav a { color: #0b5394; text-decoration: none; white-space: nowrap; }
nav a:hover { text-decoration: underline; }
h2 { font-size: 20px; margin: 32px 0 8px; padding-bottom: 3px; border-bottom: 2px solid #0072b2; }
h3 { font-size: 16px; margin: 20px 0 6px; }
p { margin: 6px 0; max-width: 80ch; }
dl.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 18px; margin: 8px 0; }
dl.facts dt { color: #555; }
dl.facts dd { margin: 0; }
pre, code { font-family: "DejaVu Sans Mono", "Liberation Mono", Menlo, Consolas, monospace; font-size: 13px; }
pre { background: #f6f6f6; border: 1px solid #e2e2e2; padding: 8px 10px; overflow-x: auto; white-space: pre-wrap; }
figure { margin: 16px 0 24px; break-inside: avoid; page-break-inside: avoid; }
figure svg { display: block; width: 100%; height: auto; max-width: 880px; }
figure.narrow svg { max-width: 560px; }
/* Each figure is drawn two-column wide and one-column wide: the one-column drawing on a phone. */
div.fig-narrow { display: none; }
div.fig-narrow svg { max-width: 520px; }
figcaption { font-size: 14px; color: #333; max-width: 80ch; margin-top: 4px; }
figcaption .files { color: #666; font-size: 12.5px; }
div.table { overflow-x: auto; margin: 8px 0 4px; }
table { border-collapse: collapse; font-size: 13px; font-variant-numeric: tabular-nums; }
th, td { padding: 2px 8px; border-bottom: 1px solid #e6e6e6; text-align: left; white-space: nowrap; }
thead th { border-bottom: 1px solid #999; font-weight: 600; }
thead tr:first-child th { border-top: 2px solid #333; }
tbody tr:last-child td { border-bottom: 2px solid #333; }
td.num, th.num { text-align: right; }
tr.section th { background: #f2f6fa; text-align: left; font-weight: 600; }
footer { margin-top: 40px; border-top: 1px solid #ddd; padding-top: 8px; color: #666; font-size: 13px; }
p.download { margin: 2px 0 12px; font-size: 13px; }
p.download a { color: #0b5394; }
dd, figcaption, pre { overflow-wrap: anywhere; }
/* A phone (390 px): one column of facts, narrower margins; wide tables scroll in their own box. */
@media (max-width: 640px) {
  main { padding: 12px 12px 32px; }
  header h1 { font-size: 21px; }
  h2 { font-size: 18px; }
  dl.facts { grid-template-columns: 1fr; gap: 0; }
  dl.facts dd { margin-bottom: 6px; }
  div.fig-wide { display: none; }
  div.fig-narrow { display: block; }
}
@media print {
  @page { size: A4; margin: 14mm 12mm; }
  body { font-size: 10pt; }
  main { max-width: none; padding: 0; }
  nav { display: none; }
  h2 { break-after: avoid; page-break-after: avoid; }
  figure svg { max-width: 100%; }
  div.fig-wide { display: block; }
  div.fig-narrow { display: none; }
  div.table { overflow: visible; }
  table { font-size: 7.5pt; }
  th, td { padding: 1px 4px; }
  pre { white-space: pre-wrap; font-size: 8pt; }
  a { color: inherit; text-decoration: none; }
  /* Paper: no download links or file lists; figures and tables keep their captions. */
  p.download, figcaption .files { display: none; }
  section { break-before: auto; }
  h3 { break-after: avoid; page-break-after: avoid; }
  div.table, table { break-inside: auto; }
  tr { break-inside: avoid; page-break-inside: avoid; }
}
)css";

}  // namespace

std::string markdown_to_html(std::string_view markdown) {
  std::ostringstream o;
  std::vector<std::string> table;
  std::string paragraph;
  auto flush = [&] {
    if (!table.empty()) o << table_html(table);
    table.clear();
    if (!paragraph.empty()) o << "<p>" << inline_markup(html_escape(paragraph)) << "</p>\n";
    paragraph.clear();
  };
  std::size_t pos = 0;
  while (pos <= markdown.size()) {
    const std::size_t nl = markdown.find('\n', pos);
    std::string_view line =
        markdown.substr(pos, nl == std::string_view::npos ? markdown.npos : nl - pos);
    pos = nl == std::string_view::npos ? markdown.size() + 1 : nl + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!line.empty() && line.front() == '|') {
      if (!paragraph.empty()) {
        o << "<p>" << inline_markup(html_escape(paragraph)) << "</p>\n";
        paragraph.clear();
      }
      table.emplace_back(line);
    } else if (line.find_first_not_of(" \t") == std::string_view::npos) {
      flush();
    } else {
      if (!table.empty()) flush();
      if (!paragraph.empty()) paragraph += ' ';
      paragraph += line;
    }
  }
  flush();
  return o.str();
}

std::string inline_svg(std::string_view svg, std::string_view id_prefix, std::string_view title) {
  std::string s(svg);
  if (s.rfind("<?xml", 0) == 0) {
    const std::size_t end = s.find("?>");
    if (end != std::string::npos) s.erase(0, s.find_first_not_of("\r\n", end + 2));
  }
  const std::string p(id_prefix);
  replace_all(s, "id=\"", "id=\"" + p);
  replace_all(s, "href=\"#", "href=\"#" + p);
  replace_all(s, "url(#", "url(#" + p);
  // The root element's fixed size (in pt) becomes the page's width; the viewBox keeps the aspect.
  const std::size_t open = s.find("<svg");
  const std::size_t close = open == std::string::npos ? open : s.find('>', open);
  if (open != std::string::npos && close != std::string::npos) {
    std::string tag = s.substr(open, close - open);
    for (const char* attr : {" width=\"", " height=\""}) {
      const std::size_t a = tag.find(attr);
      if (a == std::string::npos) continue;
      const std::size_t b = tag.find('"', a + std::string_view(attr).size());
      if (b != std::string::npos) tag.erase(a, b + 1 - a);
    }
    tag += fmt::format(" role=\"img\" aria-labelledby=\"{}title\"", p);
    s.replace(open, close - open, tag);
    const std::size_t after = s.find('>', open) + 1;
    s.insert(after, fmt::format("\n<title id=\"{}title\">{}</title>", p, html_escape(title)));
  }
  return s;
}

std::string render_html(const HtmlReport& r) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>" << html_escape(r.title) << "</title>\n<style>" << kCss << "</style>\n</head>\n"
    << "<body>\n<main>\n<header>\n<h1>" << html_escape(r.title) << "</h1>\n";
  if (!r.subtitle.empty()) o << "<p class=\"subtitle\">" << html_escape(r.subtitle) << "</p>\n";
  o << "</header>\n<nav>";
  for (const auto& s : r.sections) {
    o << "<a href=\"#" << html_escape(s.id) << "\">" << html_escape(s.heading) << "</a>";
  }
  o << "</nav>\n";
  for (const auto& s : r.sections) {
    o << "<section id=\"" << html_escape(s.id) << "\">\n<h2>" << html_escape(s.heading) << "</h2>\n"
      << s.html << "</section>\n";
  }
  if (!r.footer.empty()) o << "<footer>" << html_escape(r.footer) << "</footer>\n";
  o << "</main>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace feint::plot
