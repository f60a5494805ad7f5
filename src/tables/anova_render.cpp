// Rendering of the mixed ANOVA table (see feint/tables/anova.hpp); its numbers are computed in
// anova.cpp.
#include "feint/tables/anova.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "feint/io/number.hpp"
#include "feint/stats/effect_size.hpp"

namespace feint::tables {

namespace {

std::string join(const std::vector<std::string>& parts, std::string_view sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : std::string(sep)) + p;
  return out;
}

std::string df_text(double df) {
  if (df == std::floor(df)) return io::format_double(df);
  return format_mean(df, df < 100 ? 2 : 1);
}

/// Effect sizes and W: three decimals without the leading zero (APA style for values in [0, 1]).
std::string no_leading_zero(double x) {
  std::string s = format_mean(x, 3);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  return s;
}

/// The 95 % interval of generalized eta squared as effectsize's eta_squared(model, generalized =
/// TRUE) gives it on an afex model: the pseudo-F of ges with the uncorrected df (stats::
/// generalized_eta2), one-sided "greater" (upper bound 1).
std::optional<stats::EtaSquared> ges_interval(const models::AnovaEffect& e) {
  if (!(e.ges >= 0 && e.ges < 1 && e.num_df > 0 && e.den_df > 0)) return std::nullopt;
  return stats::generalized_eta2(e.ges, e.num_df, e.den_df, 0.95);
}

/// An all-within analysis (models::within_anova): its condition effect is within participants.
bool condition_within(const models::MixedAnova& a) {
  return std::any_of(a.effects.begin(), a.effects.end(),
                     [](const auto& e) { return e.effect == "condition" && e.within; });
}

/// The order of the error SSP matrix an effect's sphericity is about: its own numerator df in an
/// all-within analysis, k - 1 (shared by both within effects) in the split-plot one.
double sphericity_order(const models::MixedAnova& a, const models::AnovaEffect& e) {
  return condition_within(a) ? e.num_df : static_cast<double>(a.iterations.size()) - 1;
}

std::string design_text(const models::MixedAnova& a) {
  if (condition_within(a)) {
    return fmt::format(
        "condition ({} levels) \u00d7 iteration ({} levels), both within participants",
        a.conditions.size(), a.iterations.size());
  }
  if (a.one_way()) {
    return fmt::format("one-way repeated measures: iteration ({} levels) within participants",
                       a.iterations.size());
  }
  return fmt::format(
      "condition ({} levels) between \u00d7 iteration ({} levels) within participants",
      a.conditions.size(), a.iterations.size());
}

std::string sizes_text(const models::MixedAnova& a) {
  std::vector<std::string> parts;
  for (std::size_t g = 0; g < a.conditions.size(); ++g) {
    parts.push_back(a.one_way() && a.conditions[g].empty()
                        ? fmt::format("{}", a.group_sizes[g])
                        : fmt::format("{} = {}", a.conditions[g], a.group_sizes[g]));
  }
  return join(parts, ", ");
}

const models::MauchlyTest* mauchly_of(const models::MixedAnova& a, const std::string& effect) {
  for (const auto& m : a.sphericity) {
    if (m.effect == effect) return &m;
  }
  return nullptr;
}

std::string correction_name(models::SphericityCorrection c) {
  switch (c) {
    case models::SphericityCorrection::GG:
      return "Greenhouse-Geisser";
    case models::SphericityCorrection::HF:
      return "Huynh-Feldt";
    case models::SphericityCorrection::none:
      break;
  }
  return "no";
}

/// Epsilon / Mauchly cells: the number, or why there is none.
std::string sphericity_cell(const models::MixedAnova& a, const models::AnovaEffect& e,
                            std::optional<double> value, bool leading_zero = false) {
  if (!e.within) return "";
  if (sphericity_order(a, e) < 2) return "1 df";
  if (!value) return "singular";
  if (*value > 0 && *value < 0.0005) return "< .001";
  return leading_zero ? format_mean(*value, 3) : no_leading_zero(*value);
}

}  // namespace

std::string anova_apa(const models::AnovaEffect& e) {
  const auto ci = ges_interval(e);
  return fmt::format("F({}, {}) = {}, {}, \u03b7G\u00b2 = {}{}", df_text(e.report_num_df),
                     df_text(e.report_den_df), format_mean(e.f, 2), apa_p(e.report_p),
                     no_leading_zero(e.ges),
                     ci ? fmt::format(" [{}, {}]", no_leading_zero(ci->low), no_leading_zero(ci->high))
                        : std::string());
}

std::vector<std::string_view> anova_columns(bool apa) {
  std::vector<std::string_view> c = {"metric",
                                     "effect",
                                     "num_df",
                                     "den_df",
                                     "MSE",
                                     "F",
                                     "ges",
                                     "ges_low",
                                     "ges_high",
                                     "pes",
                                     "pes_low",
                                     "pes_high",
                                     "p.value",
                                     "correction",
                                     "eps",
                                     "num_df_uncorrected",
                                     "den_df_uncorrected",
                                     "p.value_uncorrected",
                                     "gg_eps",
                                     "p.value_gg",
                                     "hf_eps",
                                     "p.value_hf",
                                     "mauchly_W",
                                     "mauchly_p.value",
                                     "ss",
                                     "error_ss",
                                     "n",
                                     "n_excluded",
                                     "excluded",
                                     "note"};
  if (apa) c.push_back("apa");
  return c;
}

namespace {

std::string effect_note(const models::MixedAnova& a, const models::AnovaEffect& e) {
  std::vector<std::string> notes;
  if (!a.dropped_conditions.empty())
    notes.push_back("condition " + join(a.dropped_conditions, ", ") +
                    " dropped (every participant had a missing value; --drop-empty-conditions)");
  if (!e.correction_note.empty())
    notes.push_back(e.correction_note + "; df and p assume sphericity");
  if (e.within && sphericity_order(a, e) < 2)
    notes.push_back("1 numerator df: sphericity holds trivially");
  return join(notes, "; ");
}

/// The 95 % interval of partial eta squared from the reported F and df (effectsize's F_to_eta2:
/// noncentral F, one-sided "greater", so the upper bound is 1); empty where F is not computable.
Cell pes_bound(const models::AnovaEffect& e, bool low) {
  if (!(std::isfinite(e.f) && e.report_num_df > 0 && e.report_den_df > 0)) return Cell::none();
  const auto ci = stats::f_to_eta2(e.f, e.report_num_df, e.report_den_df, 0.95);
  return Cell::num(low ? ci.low : ci.high);
}

Cell ges_bound(const models::AnovaEffect& e, bool low) {
  const auto ci = ges_interval(e);
  return ci ? Cell::num(low ? ci->low : ci->high) : Cell::none();
}

std::vector<Record> tidy(const AnovaReport& r, bool apa) {
  std::vector<Record> out;
  for (const auto& a : r.analyses) {
    for (const auto& e : a.effects) {
      const models::MauchlyTest* m = mauchly_of(a, e.effect);
      Record rec = {Cell::str(a.metric),
                    Cell::str(e.effect),
                    Cell::num(e.report_num_df),
                    Cell::num(e.report_den_df),
                    Cell::num(e.mse),
                    Cell::num(e.f),
                    Cell::num(e.ges),
                    ges_bound(e, true),
                    ges_bound(e, false),
                    Cell::num(e.pes),
                    pes_bound(e, true),
                    pes_bound(e, false),
                    Cell::num(e.report_p),
                    Cell::str(e.within ? std::string(models::to_string(r.correction)) : "none"),
                    Cell::num(e.report_eps),
                    Cell::num(e.num_df),
                    Cell::num(e.den_df),
                    Cell::num(e.p_value),
                    Cell::num(e.gg_eps),
                    Cell::num(e.p_gg),
                    Cell::num(e.hf_eps),
                    Cell::num(e.p_hf),
                    Cell::num(m ? m->statistic : std::nullopt),
                    Cell::num(m ? m->p_value : std::nullopt),
                    Cell::num(e.ss),
                    Cell::num(e.error_ss),
                    Cell::integer(static_cast<long long>(a.n_participants)),
                    Cell::integer(static_cast<long long>(a.excluded.size())),
                    a.excluded.empty() ? Cell::none() : Cell::str(join(a.excluded, ";")),
                    [&] {
                      const std::string n = effect_note(a, e);
                      return n.empty() ? Cell::none() : Cell::str(n);
                    }()};
      if (apa) rec.push_back(Cell::str(anova_apa(e)));
      out.push_back(std::move(rec));
    }
  }
  return out;
}

/// Effect rows of one metric under its section row; the p cells also go to LaTeX as math.
void add_effect_rows(TextTable& t, const models::MixedAnova& a, bool apa) {
  const std::size_t p_col = 7, mp_col = 11;
  TextTable::Row sec;
  sec.section = true;
  sec.cells.assign(t.header.size(), "");
  sec.cells[0] = fmt::format("Metric: {}", a.metric);
  t.rows.push_back(sec);
  t.latex_cells.emplace_back(t.header.size());
  for (const auto& e : a.effects) {
    const models::MauchlyTest* m = mauchly_of(a, e.effect);
    std::vector<std::string> cells = {
        e.effect,
        df_text(e.report_num_df),
        df_text(e.report_den_df),
        format_mean(e.mse, 4),
        format_mean(e.f, 2),
        no_leading_zero(e.ges),
        no_leading_zero(e.pes),
        format_p(e.report_p) + (e.correction_note.empty() ? "" : " (a)"),
        sphericity_cell(a, e, e.gg_eps),
        sphericity_cell(a, e, e.hf_eps),
        sphericity_cell(a, e, m ? m->statistic : std::nullopt),
        m && m->p_value ? format_p(m->p_value) : sphericity_cell(a, e, std::nullopt)};
    if (!e.within) cells[mp_col] = "";
    if (apa) cells.push_back(anova_apa(e));
    std::vector<std::string> latex(t.header.size());
    latex[p_col] =
        format_p(e.report_p, PStyle::latex) + (e.correction_note.empty() ? "" : " (a)");
    if (m && m->p_value) latex[mp_col] = format_p(m->p_value, PStyle::latex);
    t.rows.push_back({std::move(cells), false});
    t.latex_cells.push_back(std::move(latex));
  }
}

/// The note of one metric: design, sample, exclusions and the sphericity remark.
std::string metric_note(const models::MixedAnova& a) {
  std::string n =
      condition_within(a)
          ? fmt::format("{}: {}; {} participants with every condition at every iteration.",
                        a.metric, design_text(a), a.n_participants)
          : fmt::format("{}: {}; {} participants with every iteration{}.", a.metric,
                        design_text(a), a.n_participants,
                        a.one_way() ? "" : " (" + sizes_text(a) + ")");
  if (!a.excluded.empty()) {
    n += fmt::format(" Excluded for a missing value (as afex): {} ({}).", a.excluded.size(),
                     join(a.excluded, ", "));
  }
  if (!a.dropped_conditions.empty())
    n += fmt::format(
        " Dropped on request (--drop-empty-conditions): condition {} (every participant had a "
        "missing value){}.",
        join(a.dropped_conditions, ", "),
        a.one_way() ? "; this is the one-way analysis of the remaining condition" : "");
  if (!a.sphericity_note.empty()) n += " (a) " + a.sphericity_note + ".";
  return n;
}

/// The note shared by every metric: the correction and what the columns mean.
std::string method_note(const AnovaReport& r) {
  const std::string within =
      r.correction == models::SphericityCorrection::none
          ? std::string("no correction (sphericity assumed)")
          : fmt::format("df multiplied by the {} epsilon, p from the corrected F distribution",
                        correction_name(r.correction));
  return fmt::format(
      "Type-III sums of squares with sum-to-zero contrasts (afex::aov_ez). Within-participant "
      "effects: {}; MSE = error SS / reported df2. ges = generalized eta squared (all factors "
      "manipulated), with its one-sided 95 % interval [ges_low, 1] as effectsize's eta_squared(generalized "
      "= TRUE) (the noncentral-F interval of the pseudo-F of ges on the uncorrected df; CSV/JSON "
      "ges_low, ges_high; APA strings), pes = partial eta squared (pes_low, pes_high: F_to_eta2 on "
      "the reported df). GG eps = Greenhouse-Geisser, HF eps = Huynh-Feldt "
      "(Lecoutre's correction, capped at 1 when applied); Mauchly's W tests sphericity (p < .05: "
      "violated). '1 df' = two iterations, sphericity holds trivially; 'singular' = fewer error df "
      "than iteration contrasts, not computable.{}",
      within, std::any_of(r.analyses.begin(), r.analyses.end(), condition_within)
                  ? " Conditions within participants (afex::aov_ez with within = c(\"condition\", "
                    "\"iteration\")): each effect is tested against its own effect \u00d7 "
                    "participant error, with its own epsilons and Mauchly test; '1 df' there = "
                    "an effect with one numerator df; ges counts every error stratum, the "
                    "participants' included."
                  : "");
}

TextTable people_table(const AnovaReport& r, bool apa) {
  TextTable t;
  t.caption = fmt::format("Mixed ANOVA (type III), {} correction of the within-participant df",
                          correction_name(r.correction));
  if (r.analyses.size() == 1 && r.analyses[0].one_way()) {
    t.caption = fmt::format("Repeated-measures ANOVA, {} correction of the df",
                            correction_name(r.correction));
  }
  if (!r.analyses.empty() && std::all_of(r.analyses.begin(), r.analyses.end(), condition_within)) {
    t.caption = fmt::format(
        "Repeated-measures ANOVA (type III), condition and iteration within participants, {} "
        "correction of the df",
        correction_name(r.correction));
  }
  t.header = {"Effect", "df1", "df2",    "MSE",    "F",         "ges",
              "pes",    "p",   "GG eps", "HF eps", "Mauchly W", "Mauchly p"};
  if (apa) t.header.push_back("APA");
  t.right_align.assign(t.header.size(), true);
  t.right_align[0] = false;
  if (apa) t.right_align.back() = false;
  for (const auto& a : r.analyses) add_effect_rows(t, a, apa);
  // The note: design, sample, exclusions, correction, and what the columns mean.
  for (const auto& a : r.analyses) t.notes.push_back(metric_note(a));
  t.notes.push_back(method_note(r));
  return t;
}

}  // namespace

namespace {

// After afex's columns; the unadjusted p of a mean or contrast goes in afex's `p.value`.
constexpr std::string_view kEmmColumns[] = {"term",     "level",     "group",      "contrast",
                                            "estimate", "std.error", "df",         "statistic",
                                            "p.adjusted", "conf.low", "conf.high", "adjust"};

TextTable emm_means_table(const AnovaReport& r, const models::MixedAnova& a,
                          const std::vector<models::EmmTable>& tables) {
  TextTable t;
  const std::string ci = io::format_double(std::round(r.emm_options.conf_level * 1e6) / 1e4) + "% CI";
  t.caption = a.metric + ": estimated marginal means (emmeans on the ANOVA, multivariate model)";
  t.header = {"Means of", "Level", "EMM", "SE", "df", ci};
  t.right_align = {false, false, true, true, true, true};
  for (const auto& tab : tables) {
    if (!tab.adjust.empty()) continue;
    for (const auto& e : tab.rows) {
      t.rows.push_back({{tab.term, e.label, fmt::format("{:.4f}", e.estimate),
                         e.computed ? fmt::format("{:.4f}", e.std_error) : "",
                         e.computed ? df_text(e.df) : "",
                         e.computed ? fmt::format("[{:.4f}, {:.4f}]", e.conf_low, e.conf_high) : ""},
                        false});
      t.latex_cells.push_back(std::vector<std::string>(6));
    }
  }
  return t;
}

TextTable emm_contrast_table(const AnovaReport& r, const models::MixedAnova& a,
                             const models::EmmTable& tab) {
  TextTable t;
  const std::string ci = io::format_double(std::round(r.emm_options.conf_level * 1e6) / 1e4) + "% CI";
  t.caption = fmt::format("{}: contrasts {} (p adjustment: {})", a.metric, tab.term, tab.adjust);
  t.header = {"By", "Contrast", "Estimate", "SE", "df", ci, "t", "p"};
  t.right_align = {false, false, true, true, true, true, true, true};
  for (const auto& e : tab.rows) {
    t.rows.push_back({{e.by, e.label, fmt::format("{:.4f}", e.estimate),
                       e.computed ? fmt::format("{:.4f}", e.std_error) : "",
                       e.computed ? df_text(e.df) : "",
                       e.computed ? fmt::format("[{:.4f}, {:.4f}]", e.conf_low, e.conf_high) : "",
                       e.computed ? fmt::format("{:.2f}", e.statistic) : "",
                       e.computed ? format_p(e.p_value) : std::string(kNotComputable)},
                      false});
    std::vector<std::string> latex(8);
    if (e.computed) latex[7] = format_p(e.p_value, PStyle::latex);
    t.latex_cells.push_back(std::move(latex));
  }
  return t;
}

}  // namespace

namespace {

// Where the emmeans columns sit in a tidy record: after afex's, plus afex's p.value column.
struct EmmLayout {
  std::size_t size = 0;     ///< columns in all
  std::size_t n_anova = 0;  ///< afex's columns, `table` included; kEmmColumns start here
  std::size_t p_col = 0;    ///< afex's `p.value`
};

// One estimated mean ("emmean") or contrast ("emm_contrast") as a tidy record.
Record emm_record(const std::string& metric, const models::EmmTable& tab,
                  const models::EmmRow& e, const EmmLayout& layout) {
  Record rec(layout.size);
  const bool means = tab.adjust.empty();
  rec[0] = Cell::str(means ? "emmean" : "emm_contrast");
  rec[1] = Cell::str(metric);
  auto at = [&](std::size_t k) -> Cell& { return rec[layout.n_anova + k]; };
  at(0) = Cell::str(tab.term);
  if (means) {
    at(1) = Cell::str(e.label);
  } else {
    if (!e.by.empty()) at(2) = Cell::str(e.by);
    at(3) = Cell::str(e.label);
    at(11) = Cell::str(tab.adjust);
  }
  at(4) = Cell::num(e.estimate);
  if (e.computed) {
    at(5) = Cell::num(e.std_error);
    at(6) = Cell::num(e.df);
    at(7) = Cell::num(e.statistic);
    rec[layout.p_col] = Cell::num(e.p_unadjusted);
    if (!means) at(8) = Cell::num(e.p_value);
    at(9) = Cell::num(e.conf_low);
    at(10) = Cell::num(e.conf_high);
  }
  return rec;
}

// A `table` column first (anova, emmean, emm_contrast), and emmeans' columns after afex's; the
// ANOVA records are widened to match and the emmeans records follow them.
void add_emm_records(const AnovaReport& r, std::vector<std::string_view>& cols,
                     std::vector<Record>& recs) {
  cols.insert(cols.begin(), "table");
  EmmLayout layout;
  layout.n_anova = cols.size();
  layout.p_col = static_cast<std::size_t>(
      std::find(cols.begin(), cols.end(), std::string_view("p.value")) - cols.begin());
  cols.insert(cols.end(), std::begin(kEmmColumns), std::end(kEmmColumns));
  layout.size = cols.size();
  for (auto& rec : recs) {
    rec.insert(rec.begin(), Cell::str("anova"));
    rec.resize(cols.size());
  }
  for (std::size_t i = 0; i < r.analyses.size() && i < r.emm.size(); ++i)
    for (const auto& tab : r.emm[i])
      for (const auto& e : tab.rows)
        recs.push_back(emm_record(r.analyses[i].metric, tab, e, layout));
}

std::string render_anova_tidy(const AnovaReport& r, OutputFormat format, bool apa) {
  auto cols = anova_columns(apa);
  auto recs = tidy(r, apa);
  if (r.emm_options.any()) add_emm_records(r, cols, recs);
  return format == OutputFormat::csv ? write_csv(cols, recs) : write_json(cols, recs);
}

// The means and contrast tables of one analysis; the last carries the note on how emmeans
// computes them. Labels derive from the main table's (`base`).
std::vector<TextTable> emm_tables(const AnovaReport& r, std::size_t i, const std::string& base) {
  const std::string id = latex_label_part(r.analyses[i].metric);
  std::vector<TextTable> tables;
  if (r.emm_options.emmeans) {
    tables.push_back(emm_means_table(r, r.analyses[i], r.emm[i]));
    tables.back().latex_label = base + "-emmeans-" + id;
  }
  std::size_t k = 0;
  for (const auto& tab : r.emm[i])
    if (!tab.adjust.empty()) {
      tables.push_back(emm_contrast_table(r, r.analyses[i], tab));
      tables.back().latex_label = base + "-emm-contrasts-" + id + "-" + std::to_string(++k);
    }
  if (!tables.empty())
    tables.back().notes.push_back(
        "Estimated marginal means and contrasts as emmeans on the afex::aov_ez object with "
        "its default multivariate model: cell means of the complete participants, each "
        "contrast's SE from the covariance of the iterations pooled within conditions, df = "
        "N - a. Equal weights over the cells; each by-group is one family for the "
        "adjustment; Holm gives Bonferroni intervals (as emmeans); Tukey uses exact "
        "studentized-range quantiles.");
  return tables;
}

// The emmeans tables of every analysis, each after a blank line.
std::string render_emm_tables(const AnovaReport& r, OutputFormat format,
                              const TablePresentation& presentation) {
  std::string out;
  const std::string base = presentation.label.empty() ? "tab:feint-anova" : presentation.label;
  for (std::size_t i = 0; i < r.analyses.size() && i < r.emm.size(); ++i) {
    for (auto& tt : emm_tables(r, i, base)) {
      tt.latex_wide = presentation.wide;
      out += "\n" + render_table(tt, format);
    }
  }
  return out;
}

}  // namespace

std::string render_anova(const AnovaReport& r, OutputFormat format, bool apa,
                         const TablePresentation& presentation) {
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    return render_anova_tidy(r, format, apa);
  }
  TextTable t = people_table(r, apa);
  apply_presentation(t, presentation, "tab:feint-anova");
  std::string out = render_table(t, format);
  if (r.emm_options.any()) out += render_emm_tables(r, format, presentation);
  return out;
}

}  // namespace feint::tables
