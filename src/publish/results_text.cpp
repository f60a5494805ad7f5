// The Results paragraphs (see feint/publish/results_text.hpp and docs/report.md "Results text").
#include "feint/publish/results_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "feint/io/html_escape.hpp"
#include "feint/tables/writers.hpp"

namespace feint::publish {

namespace {

using analysis::Finding;
using analysis::Hypothesis;
using analysis::Strength;

// A statistical symbol in each format: italic in Markdown and HTML, math in LaTeX.
struct Sym {
  std::string md, html, tex;
};
Sym italic(const std::string& s) { return {"*" + s + "*", "<i>" + s + "</i>", s}; }

// How one format writes text, numbers and "symbol = value".
struct Style {
  ResultsFormat format;

  std::string text(std::string_view s) const {
    if (format == ResultsFormat::latex) return tables::latex_escape(s);
    if (format == ResultsFormat::html) return io::html_escape(s);
    return std::string(s);
  }
  // A number's minus: U+2212 in prose, "-" in LaTeX's math (which typesets a minus).
  std::string signed_text(std::string s) const {
    if (!s.empty() && s.front() == '-' && format != ResultsFormat::latex) s = "\u2212" + s.substr(1);
    return s;
  }
  std::string number(double v, int decimals) const {
    std::string s = fmt::format("{:.{}f}", v, decimals);
    if (s.front() == '-' && s.find_first_not_of("0.", 1) == std::string::npos) s.erase(0, 1);
    return signed_text(s);
  }
  // "*t*(57.50) = 2.31", "<i>t</i>(57.50) = 2.31", "$t(57.50) = 2.31$".
  std::string eq(const Sym& s, std::string_view args, std::string_view rel, std::string_view value) const {
    switch (format) {
      case ResultsFormat::latex: return fmt::format("${}{} {} {}$", s.tex, args, rel, value);
      // No-break spaces: "p = .023" is never split over two lines of a phone's screen.
      case ResultsFormat::html: {
        std::string a(args);
        for (auto k = a.find(", "); k != std::string::npos; k = a.find(", ", k)) a.replace(k, 2, ",\u00a0");
        return fmt::format("{}{}\u00a0{}\u00a0{}", s.html, a, io::html_escape(rel), value);
      }
      case ResultsFormat::markdown: break;
    }
    return fmt::format("{}{} {} {}", s.md, args, rel, value);
  }
  std::string symbol(const Sym& s) const {
    if (format == ResultsFormat::latex) return "$" + s.tex + "$";
    return format == ResultsFormat::html ? s.html : s.md;
  }
  // "95% CI [0.01, 0.11]"; a one-sided interval open at its infinite end, as R gives it: "[0.01, ∞)".
  std::string ci(double level, const std::string& low, const std::string& high) const {
    const std::string pct = fmt::format("{:g}{} CI", 100 * level, format == ResultsFormat::latex ? "\\%" : "%");
    const bool tex = format == ResultsFormat::latex;
    const std::string lo = low.empty() ? (tex ? "(-\\infty" : "(\u2212\u221e") : "[" + low;
    const std::string hi = high.empty() ? (tex ? "\\infty)" : "\u221e)") : high + "]";
    if (tex) return fmt::format("{} ${}, {}$", pct, lo, hi);
    if (format == ResultsFormat::html)
      return fmt::format("{:g}%\u00a0CI\u00a0{},\u00a0{}", 100 * level, lo, hi);
    return fmt::format("{} {}, {}", pct, lo, hi);
  }
  std::string minus_between(std::string_view lhs, std::string_view rhs) const {
    if (format == ResultsFormat::latex) return text(lhs) + " $-$ " + text(rhs);
    return text(lhs) + " \u2212 " + text(rhs);
  }
};

bool finite(const std::optional<double>& v) { return v && std::isfinite(*v); }
// An interval's bound: finite, or the infinite end of a one-sided interval.
bool bound(const std::optional<double>& v) { return v && !std::isnan(*v); }

std::string capitalised(std::string s) {
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

// "a", "a and b", "a, b, and c" (APA's serial comma).
std::string listed(const std::vector<std::string>& items) {
  std::string o;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) o += items.size() == 2 ? " and " : (i + 1 == items.size() ? ", and " : ", ");
    o += items[i];
  }
  return o;
}

// A correlation-like value (|r| <= 1): no leading zero, as APA writes r and eta squared.
std::string proportion(const Style& st, double v) {
  std::string s = st.number(v, 2);
  for (const char* zero : {"0.", "-0.", "\u22120."}) {
    const std::string z(zero);
    if (s.rfind(z, 0) == 0) s.erase(z.size() - 2, 1);
  }
  return s;
}

// Two decimals, three when every number of the finding is below 0.1 in size (slopes per exposure).
int decimals_of(const Finding& f) {
  double m = 0;
  for (const auto& v : {f.estimate, f.ci_low, f.ci_high})
    if (finite(v)) m = std::max(m, std::fabs(*v));
  if (f.means)
    for (const double v : {f.means->first, f.means->second})
      if (std::isfinite(v)) m = std::max(m, std::fabs(v));
  return m > 0 && m < 0.1 ? 3 : 2;
}

// The two sides of "A - B" ("adaptive - random", "mean - 3.5"); empty when not of that form.
std::pair<std::string, std::string> sides(const std::string& s, std::string_view op) {
  const std::string sep = fmt::format(" {} ", op);
  const auto k = s.find(sep);
  if (k == std::string::npos) return {};
  return {s.substr(0, k), s.substr(k + sep.size())};
}

bool one_sample(const Finding& f) { return sides(f.contrast, "-").first == "mean"; }

}  // namespace

std::size_t word_count(std::string_view text) {
  std::size_t n = 0;
  bool in_word = false;
  for (const char c : text) {
    const bool space = c == ' ' || c == '\n' || c == '\t' || c == '\r';
    if (!space && !in_word) ++n;
    in_word = !space;
  }
  return n;
}

namespace {

// +1 when the finding leans A > B, -1 for A < B; nullopt when it does not say (an F test without
// an estimate) or when its sides are not A and B.
std::optional<int> lean(const Finding& f, std::string_view a) {
  std::string lhs, rhs;
  int sign = 0;
  if (finite(f.estimate) && !f.contrast.empty()) {
    std::tie(lhs, rhs) = sides(f.contrast, "-");
    sign = *f.estimate > 0 ? 1 : *f.estimate < 0 ? -1 : 0;
  } else {
    for (const char* op : {">", "<"}) {
      auto s = sides(f.direction, op);
      if (!s.first.empty()) {
        std::tie(lhs, rhs) = s;
        sign = op[0] == '>' ? 1 : -1;
      }
    }
  }
  if (sign == 0 || lhs.empty()) return std::nullopt;
  if (a.empty() || lhs == a) return sign;
  if (rhs == a) return -sign;
  return std::nullopt;
}

}  // namespace

Answer answer(const Hypothesis& h, const Finding& f, std::string_view a) {
  switch (f.strength) {
    case Strength::no_evidence_either_way: return Answer::inconclusive;
    case Strength::evidence_for_no_difference: return Answer::no_difference;
    case Strength::not_computable: return Answer::not_testable;
    case Strength::evidence_for_difference: break;
  }
  if (h.direction != "greater" && h.direction != "less") return Answer::supported;
  const auto l = lean(f, a);
  if (!l) return Answer::undirected;
  return *l == (h.direction == "greater" ? 1 : -1) ? Answer::supported : Answer::contradicted;
}

namespace {

// ------------------------------------------------------------------------------------------------
// The numbers of one finding

// The test's statistic as the finding's APA statistics give it ("t(57.50) = 2.31" before ", p =
// .023"), only when that p is the finding's own. Not for a family: its statistics may be another
// member's than its numbers (the first with evidence against the smallest adjusted p), which a
// rounded p cannot tell apart.
std::string statistic(const Style& st, const Finding& f) {
  if (!finite(f.p) || !f.member.empty()) return {};
  const std::string p = tables::apa_p(*f.p);
  auto k = f.statistics.find(", " + p);
  if (k == std::string::npos && *f.p >= 0.9995) k = f.statistics.find(", p = 1.000");
  if (k == std::string::npos || f.statistics.rfind("not computable", 0) == 0) return {};
  std::string clause = f.statistics.substr(0, k);
  std::string prefix;
  if (clause.rfind("TOST: ", 0) == 0) {
    prefix = "TOST: ";
    clause.erase(0, 6);
  }
  const auto eq = clause.find(" = ");
  if (eq == std::string::npos || clause.substr(eq + 3) == "NA") return {};
  std::string name = clause.substr(0, eq), args;
  const auto paren = name.find('(');
  if (paren != std::string::npos) {
    args = name.substr(paren);
    name.erase(paren);
  }
  Sym sym = italic(name);
  if (name == "\u03c7\u00b2") sym = {"*\u03c7*\u00b2", "<i>\u03c7</i>\u00b2", "\\chi^2"};
  return st.text(prefix) + st.eq(sym, args, "=", st.signed_text(clause.substr(eq + 3)));
}

std::string p_value(const Style& st, double p) {
  const std::string s = tables::apa_p(p);  // "p = .023", "p < .001", "p > .999"
  return st.eq(italic("p"), "", s.substr(2, 1), s.substr(4));
}

// "BF₁₀ = 3.21" or, below 1, "BF₀₁ = 4.50" (tables::apa_bayes_factor, as the tables print it).
std::string bayes_factor(const Style& st, double bf10) {
  const std::string s = tables::apa_bayes_factor(std::log(bf10));
  const bool for01 = s.find("\u2080\u2081") != std::string::npos;
  const auto space = s.find(' ');
  const std::string rel = s.substr(space + 1, 1);
  std::string value = s.substr(space + 3);
  if (st.format == ResultsFormat::latex) {
    const auto e = value.find('e');
    if (e != std::string::npos) {
      const std::string mantissa = value.substr(0, e);
      const int exponent = std::stoi(value.substr(e + 1));
      value = mantissa == "1" ? fmt::format("10^{{{}}}", exponent)
                              : fmt::format("{} \\times 10^{{{}}}", mantissa, exponent);
    }
  }
  const std::string digits = for01 ? "01" : "10";
  const Sym sym{s.substr(0, space), "BF<sub>" + digits + "</sub>", "\\mathrm{BF}_{" + digits + "}"};
  return st.eq(sym, "", rel, value);
}

// "d = 0.53, 95% CI [0.12, 0.94]", "partial η² = .08, 95% CI [.00, .21]".
std::string effect_size(const Style& st, const Finding& f) {
  if (!f.effect_size || !std::isfinite(f.effect_size->value)) return {};
  const auto& e = *f.effect_size;
  const bool r_like =
      e.name == "r_rb" || e.name.rfind("eta2", 0) == 0 || e.name == "epsilon2_rank" || e.name == "cramers_v" ||
      e.name == "omega2";
  auto value = [&](double v) { return r_like ? proportion(st, v) : st.number(v, 2); };
  std::string lead;
  Sym sym = italic(e.name);
  if (e.name == "d_z") sym = {"*d*z", "<i>d</i><sub>z</sub>", "d_z"};
  if (e.name == "r_rb") lead = "rank-biserial ", sym = italic("r");
  if (e.name == "odds_ratio") lead = "odds ratio ", sym = {"OR", "OR", "\\mathrm{OR}"};
  if (e.name == "eta2_p") lead = "partial ";
  if (e.name == "eta2_G") lead = "generalized ";
  if (e.name.rfind("eta2", 0) == 0) sym = {"*\u03b7*\u00b2", "<i>\u03b7</i>\u00b2", "\\eta^2"};
  if (e.name == "epsilon2_rank") lead = "rank ", sym = {"*\u03b5*\u00b2", "<i>\u03b5</i>\u00b2", "\\varepsilon^2"};
  if (e.name == "omega2") sym = {"*\u03c9*\u00b2", "<i>\u03c9</i>\u00b2", "\\omega^2"};
  // A yes/no question across three or more conditions (docs/yes-no.md): effectsize's default V.
  if (e.name == "cramers_v") lead = "bias-corrected Cram\u00e9r's ", sym = italic("V");
  std::string o = lead + st.eq(sym, "", "=", value(e.value));
  // Proportions of variance and V carry effectsize's one-sided interval (upper bound 1): say so,
  // or "[.02, 1.00]" reads as a two-sided interval that reaches 1.
  const bool one_sided = (e.name.rfind("eta2", 0) == 0 || e.name == "omega2" || e.name == "cramers_v") &&
                         e.ci_high && *e.ci_high == 1.0;
  if (bound(e.ci_low) && bound(e.ci_high) && (finite(e.ci_low) || finite(e.ci_high)))
    o += std::string(", ") + (one_sided ? "one-sided " : "") +
         st.ci(f.conf_level, finite(e.ci_low) ? value(*e.ci_low) : "", finite(e.ci_high) ? value(*e.ci_high) : "");
  return o;
}

// "Welch t test (test 3, the family's smallest adjusted p), t(57.50) = 2.31, p = .023, adjusted
// p = .046, BF₁₀ = 3.21".
std::string test_part(const Style& st, const Finding& f) {
  std::vector<std::string> items;
  std::string name = st.text(f.test);
  if (!f.member.empty())
    name += (name.empty() ? "" : " ") + fmt::format("({}, the family's smallest adjusted {})",
                                                    st.text(f.member), st.symbol(italic("p")));
  if (!name.empty()) items.push_back(name);
  if (auto s = statistic(st, f); !s.empty()) items.push_back(s);
  if (finite(f.p)) items.push_back(p_value(st, *f.p));
  if (finite(f.p_adjusted)) items.push_back("adjusted " + p_value(st, *f.p_adjusted));
  if (f.bf10 && *f.bf10 > 0 && std::isfinite(*f.bf10)) items.push_back(bayes_factor(st, *f.bf10));
  else if (!f.bf_note.empty()) items.push_back("no Bayes factor");
  std::string o;
  for (const auto& i : items) o += (o.empty() ? "" : ", ") + i;
  return o;
}

// "error: adaptive M = 0.61, random M = 0.55; difference (adaptive − random) 0.06, 95% CI [0.01,
// 0.11]; d = 0.53, 95% CI [0.12, 0.94]; Welch t test, t(57.50) = 2.31, p = .023, ...: moderate
// evidence for a difference."
std::string measure_sentence(const Style& st, const std::string& measure, const Finding* f) {
  const std::string head = st.text(capitalised(measure)) + ": ";
  if (!f) return head + "no result was computed.";
  if (f->strength == Strength::not_computable)
    return head + (f->sentence.empty() ? std::string("not computable.") : st.text(f->sentence));
  const int dec = decimals_of(*f);
  auto value = [&](double v) {
    const std::string s = st.number(v, dec);
    return st.format == ResultsFormat::latex ? "$" + s + "$" : s;
  };
  const auto [lhs, rhs] = sides(f->contrast, "-");
  std::vector<std::string> parts;
  if (f->means && std::isfinite(f->means->first) && std::isfinite(f->means->second)) {
    const std::string m1 = st.eq(italic("M"), "", "=", st.number(f->means->first, dec));
    if (one_sample(*f))
      parts.push_back(fmt::format("{} (reference {})", m1, value(f->means->second)));
    else if (!lhs.empty())
      parts.push_back(fmt::format("{} {}, {} {}", st.text(lhs), m1, st.text(rhs),
                                  st.eq(italic("M"), "", "=", st.number(f->means->second, dec))));
    else
      parts.push_back(fmt::format("{} and {}", m1, value(f->means->second)));
  }
  if (finite(f->estimate)) {
    std::string d = "difference";
    if (!lhs.empty()) d += " (" + st.minus_between(lhs, rhs) + ")";
    d += " " + value(*f->estimate);
    if (bound(f->ci_low) && bound(f->ci_high) && (finite(f->ci_low) || finite(f->ci_high)))
      d += ", " + st.ci(f->conf_level, finite(f->ci_low) ? st.number(*f->ci_low, dec) : "",
                        finite(f->ci_high) ? st.number(*f->ci_high, dec) : "");
    parts.push_back(d);
  }
  if (auto e = effect_size(st, *f); !e.empty()) parts.push_back(e);
  if (auto t = test_part(st, *f); !t.empty()) parts.push_back(t);
  std::string o = head;
  for (std::size_t i = 0; i < parts.size(); ++i) o += (i ? "; " : "") + parts[i];
  const std::string evidence = f->evidence.empty() ? analysis::to_string(f->strength) : f->evidence;
  return o + (parts.empty() ? "" : ": ") + st.text(evidence) + ".";
}

// ------------------------------------------------------------------------------------------------
// A hypothesis's measures and their headline findings

struct MeasureResult {
  std::string measure;
  std::vector<const Finding*> findings;
  const Finding* headline = nullptr;
};

// True when a hypothesis about a pair (h.pair) is not answered by f: a test across all the
// conditions, or a contrast of another pair ("adaptive - fixed-block"; an exposure contrast names
// its sides "A slope - B slope").
bool answers_another_question(const Finding& f, const Hypothesis& h) {
  if (h.pair.size() != 2) return false;
  if (f.omnibus) return true;
  auto [lhs, rhs] = sides(f.contrast, "-");
  if (lhs.empty() || lhs == "mean") return false;
  for (std::string* side : {&lhs, &rhs})
    if (side->size() > 6 && side->ends_with(" slope")) side->resize(side->size() - 6);
  return !((lhs == h.pair[0] && rhs == h.pair[1]) || (lhs == h.pair[1] && rhs == h.pair[0]));
}

// Which finding of a measure speaks for it (results_paragraphs): lower is better.
int headline_rank(const Finding& f, const Hypothesis& h) {
  if (f.strength == Strength::not_computable) return 4;
  if (answers_another_question(f, h)) return 3;
  if (f.omnibus) return -1;  // the test across the conditions, before any of their pairs
  const bool comparison = !one_sample(f) && (!f.contrast.empty() || !f.direction.empty());
  if (comparison && f.member.empty() && f.means && finite(f.estimate)) return 0;
  if (comparison && finite(f.estimate)) return 1;
  return comparison ? 2 : 3;
}

const Finding* headline_of(const std::vector<const Finding*>& fs, const Hypothesis& h) {
  const bool confirmatory = std::any_of(fs.begin(), fs.end(), [](const Finding* f) { return f->confirmatory; });
  // A confirmatory hypothesis with a direction speaks through its one-sided tests.
  const bool one_sided = std::any_of(fs.begin(), fs.end(), [](const Finding* f) {
    return f->confirmatory && f->alternative != stats::Alternative::two_sided && f->strength != Strength::not_computable;
  });
  const Finding* best = nullptr;
  int best_rank = 5;
  for (const Finding* f : fs) {
    if (confirmatory && !f->confirmatory) continue;
    if (one_sided && f->alternative == stats::Alternative::two_sided) continue;
    const int r = headline_rank(*f, h);
    if (r < best_rank) best = f, best_rank = r;
  }
  return best;
}

// The declared measures first (a declared measure without a finding is "not testable", unless the
// findings name measures of their own, as the questionnaire's items), then the others in order.
std::vector<MeasureResult> measures_of(const Hypothesis& h, std::span<const Finding> findings) {
  std::vector<MeasureResult> found;
  for (const auto& f : findings) {
    if (f.hypothesis != h.id || f.measure.empty()) continue;
    auto it = std::find_if(found.begin(), found.end(), [&](const auto& m) { return m.measure == f.measure; });
    if (it == found.end()) it = found.insert(found.end(), MeasureResult{f.measure, {}, nullptr});
    it->findings.push_back(&f);
  }
  auto declared = [&](const std::string& m) {
    return std::find(h.measures.begin(), h.measures.end(), m) != h.measures.end();
  };
  const bool own_measures = std::any_of(found.begin(), found.end(), [&](const auto& m) { return !declared(m.measure); });
  std::vector<MeasureResult> out;
  for (const auto& m : h.measures) {
    auto it = std::find_if(found.begin(), found.end(), [&](const auto& r) { return r.measure == m; });
    if (it != found.end()) out.push_back(*it);
    else if (!own_measures) out.push_back({m, {}, nullptr});
  }
  for (const auto& r : found)
    if (!declared(r.measure)) out.push_back(r);
  for (auto& r : out) r.headline = headline_of(r.findings, h);
  return out;
}

// ------------------------------------------------------------------------------------------------
// The paragraph

// "H1 was supported for error but inconclusive for confusion."
std::string answer_sentence(const Style& st, const Hypothesis& h, const std::vector<MeasureResult>& ms,
                            std::string_view a) {
  static constexpr std::pair<Answer, const char*> kPhrases[] = {
      {Answer::supported, "supported for {}"},
      {Answer::contradicted, "contradicted for {} (a difference in the other direction)"},
      {Answer::undirected, "undecided for {} (a difference whose direction the test does not give)"},
      {Answer::no_difference, "not supported for {} (evidence for no difference)"},
      {Answer::inconclusive, "inconclusive for {}"},
      {Answer::not_testable, "not testable for {}"},
  };
  if (ms.empty()) return st.text(h.id) + " could not be tested: no finding answers it.";
  std::vector<std::string> phrases;
  bool supported_first = false;
  for (const auto& [kind, phrase] : kPhrases) {
    std::vector<std::string> names;
    for (const auto& m : ms)
      if ((m.headline ? answer(h, *m.headline, a) : Answer::not_testable) == kind) names.push_back(st.text(m.measure));
    if (names.empty()) continue;
    if (phrases.empty()) supported_first = kind == Answer::supported;
    phrases.push_back(fmt::format(fmt::runtime(phrase), listed(names)));
  }
  std::string o = st.text(h.id) + " was " + phrases[0];
  for (std::size_t i = 1; i < phrases.size(); ++i) {
    const bool last = i + 1 == phrases.size();
    const char* joint = i == 1 && supported_first ? " but " : phrases.size() == 2 ? " and " : last ? ", and " : ", ";
    o += joint + phrases[i];
  }
  return o + ".";
}

// "The 14 other findings on H1 (2 with evidence for a difference, 12 with no evidence either way)
// are in the tables."
std::string others_sentence(const Style& st, const Hypothesis& h, const std::vector<MeasureResult>& ms,
                            std::span<const Finding> findings) {
  std::size_t counts[4] = {0, 0, 0, 0};
  std::size_t n = 0;
  for (const auto& f : findings) {
    if (f.hypothesis != h.id) continue;
    if (std::any_of(ms.begin(), ms.end(), [&](const auto& m) { return m.headline == &f; })) continue;
    ++counts[static_cast<int>(f.strength)];
    ++n;
  }
  if (n == 0) return {};
  static constexpr const char* kWith[] = {"with evidence for a difference", "with no evidence either way",
                                          "with evidence for no difference", "not computable"};
  std::vector<std::string> parts;
  for (int k : {0, 2, 1, 3})
    if (counts[k]) parts.push_back(fmt::format("{} {}", counts[k], kWith[k]));
  if (n == 1) {
    const int k = static_cast<int>(std::find_if(std::begin(counts), std::end(counts), [](auto c) { return c > 0; }) - counts);
    return fmt::format("The other finding on {} ({}) is in the tables.", st.text(h.id),
                       analysis::to_string(static_cast<Strength>(k)));
  }
  return fmt::format("The {} other findings on {} ({}) are in the tables.", n, st.text(h.id), listed(parts));
}

// How much of a paragraph is shown: the first `shown` measures' numbers, the statement's first
// `statement_words` words (all, unless a statement alone would break the cap).
struct Layout {
  std::size_t shown = 0;
  std::size_t statement_words = static_cast<std::size_t>(-1);
};

std::string paragraph(const Style& st, const Hypothesis& h, const std::vector<MeasureResult>& ms,
                      std::span<const Finding> findings, std::string_view a, const Layout& l) {
  std::string statement = h.statement;
  if (word_count(statement) > l.statement_words) {
    std::size_t words = 0, k = 0;
    for (bool in = false; k < statement.size(); ++k) {
      const bool space = statement[k] == ' ';
      if (!space && !in && ++words > l.statement_words) break;
      in = !space;
    }
    statement = statement.substr(0, k);
    while (!statement.empty() && statement.back() == ' ') statement.pop_back();
    statement += " ...";
  }
  const std::string kind = h.confirmatory ? "confirmatory" : "exploratory";
  std::string id = st.text(h.id);
  if (st.format == ResultsFormat::markdown) id = "**" + id + "**";
  if (st.format == ResultsFormat::html) id = "<strong>" + id + "</strong>";
  std::string o = fmt::format("{} ({}): {}", id, kind, st.text(statement));
  // No finding at all (e.g. H2 of a study without a questionnaire): one sentence says so.
  if (!ms.empty() && std::none_of(ms.begin(), ms.end(), [](const MeasureResult& m) { return m.headline; })) {
    std::vector<std::string> names;
    for (const auto& m : ms) names.push_back(st.text(m.measure));
    std::string answer = fmt::format("{} could not be tested: the study has no results on {}.", st.text(h.id),
                                     listed(names));
    if (st.format == ResultsFormat::html) answer = "<strong>" + answer + "</strong>";
    return o + " " + answer;
  }
  for (std::size_t i = 0; i < l.shown && i < ms.size(); ++i)
    o += " " + measure_sentence(st, ms[i].measure, ms[i].headline);
  if (l.shown < ms.size()) {
    std::vector<std::string> rest;
    for (std::size_t i = l.shown; i < ms.size(); ++i) rest.push_back(st.text(ms[i].measure));
    o += fmt::format(" The results on {} are in the tables.", listed(rest));
  }
  if (auto others = others_sentence(st, h, ms, findings); !others.empty()) o += " " + others;
  std::string answer = answer_sentence(st, h, ms, a);
  if (st.format == ResultsFormat::html) answer = "<strong>" + answer + "</strong>";
  return o + " " + answer;
}

// The most the cap allows, counted on the Markdown (the other formats have the same words).
Layout fit(const Hypothesis& h, const std::vector<MeasureResult>& ms, std::span<const Finding> findings,
           std::string_view a) {
  const Style md{ResultsFormat::markdown};
  Layout l;
  l.shown = ms.size();
  auto words = [&] { return word_count(paragraph(md, h, ms, findings, a, l)); };
  while (l.shown > 0 && words() > kResultsWordCap) --l.shown;
  if (words() > kResultsWordCap) {
    l.statement_words = word_count(h.statement);
    while (l.statement_words > 0 && words() > kResultsWordCap) --l.statement_words;
  }
  return l;
}

}  // namespace

std::vector<std::string> results_paragraphs(std::span<const Hypothesis> hypotheses,
                                            std::span<const Finding> findings, ResultsFormat format,
                                            std::string_view a) {
  std::vector<std::string> out;
  for (const auto& h : hypotheses) {
    const auto ms = measures_of(h, findings);
    out.push_back(paragraph(Style{format}, h, ms, findings, a, fit(h, ms, findings, a)));
  }
  return out;
}

std::string study_results_text(const analysis::StudyResults& r, ResultsFormat format) {
  if (r.hypotheses.empty()) {
    const std::string none =
        "No hypothesis was tested: the study compares no two conditions (compare = \"A,B\" in its "
        "feint.toml).";
    if (format == ResultsFormat::html) return "<p class=\"results-text\">" + io::html_escape(none) + "</p>\n";
    return (format == ResultsFormat::latex ? tables::latex_escape(none) : none) + "\n";
  }
  const std::string a = r.comparison && r.comparison->options.compare ? r.comparison->options.compare->first : "";
  return results_text(r.hypotheses, r.findings, format, a);
}

std::string results_text(const std::vector<Hypothesis>& hypotheses, std::span<const Finding> findings,
                         ResultsFormat format, std::string_view a) {
  std::string o;
  if (format == ResultsFormat::latex)
    o = "% The Results paragraphs of feint analyze: one per hypothesis (docs/report.md, \"Results text\").\n\n";
  const auto ps = results_paragraphs(hypotheses, findings, format, a);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (format == ResultsFormat::html)
      o += fmt::format("<p class=\"results-text\" id=\"results-{}\">{}</p>\n", io::html_escape(hypotheses[i].id), ps[i]);
    else
      o += (i ? "\n" : "") + ps[i] + "\n";
  }
  return o;
}

}  // namespace feint::publish
