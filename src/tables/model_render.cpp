// `feint model`'s tables as text, Markdown, LaTeX, CSV and JSON, and their notes (see
// feint/tables/model.hpp); the numbers are computed in model.cpp.
#include "feint/tables/model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/models/exposure.hpp"

namespace feint::tables {

namespace {

std::string whole_or_double(double v) { return io::format_double(v); }

std::string fixed(std::optional<double> v, int decimals) { return format_mean(v, decimals); }

std::string df_text(double df) {
  if (df == std::floor(df)) return fmt::format("{}", static_cast<long long>(df));
  return fmt::format("{:.1f}", df);
}

std::string percent(double conf) { return io::format_double(std::round(conf * 1e6) / 1e4); }

}  // namespace

std::string apa_model_df(double df) {
  std::string s = fmt::format("{:.1f}", df);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

std::string anova_apa(const models::AnovaTerm& a) {
  if (!a.computed) return fmt::format("{}: {}", kNotComputable, a.note);
  return fmt::format("F({}, {}) = {:.2f}, {}", apa_model_df(a.num_df), apa_model_df(a.den_df), a.f, apa_p(a.p));
}

namespace {

// The model, how time enters it (iteration as factor or trend, or exposure) and its fit.
std::string model_note(const ModelOptions& o, const MetricModel& m) {
  const std::string time_text =
      o.exposure ? "exposure = how many times the participant had already seen the trial's "
                   "strategy (0 at the first exposure), as a linear covariate"
      : o.trend  ? "iteration as a linear trend"
                 : "iteration as a factor";
  return fmt::format(
      "Linear mixed model {} ({}{}; R's treatment coding), fitted by REML as lme4::lmer (REML "
      "criterion {:.4f}).",
      m.formula, time_text, o.condition_within ? "; condition within participants" : "",
      m.fit.reml_criterion);
}

std::string f_test_note(bool kenward_roger) {
  return kenward_roger
             ? "Type III F tests with Kenward-Roger's adjusted covariance, denominator degrees of "
               "freedom and F scaling (Kenward & Roger 1997), as lmerTest::anova(m, ddf = "
               "\"Kenward-Roger\") / pbkrtest::KRmodcomp; Sum Sq and Mean Sq are lmerTest's "
               "(unscaled Wald F times sigma^2)."
             : "Type III F tests with Satterthwaite's denominator degrees of freedom, as "
               "lmerTest::anova(m) (its type-III hypotheses do not depend on the contrast coding).";
}

// Participants (per condition when there are several) and trials.
std::string sample_note(const MetricModel& m) {
  std::string groups;
  for (const auto& [g, n] : m.participants_per_group)
    if (m.participants_per_group.size() > 1)
      groups += fmt::format("{}{} in {}", groups.empty() ? "" : ", ", n, g.empty() ? "all" : g);
  return fmt::format("{} participants{}, {} trials.", m.fit.participants.size(),
                     groups.empty() ? "" : " (" + groups + ")", m.fit.n_obs);
}

// The mixed model keeps participants with missing trials; say so, since the ANOVA does not.
std::string missing_trials_note(const MetricModel& m, bool condition_within) {
  if (m.trials_missing == 0) return "No missing trials.";
  return fmt::format(
      "{} participant x {}iteration trial{} without a value of {} (empty or absent); the {} "
      "participant{} with missing trials {} kept with {} other trials (unlike the "
      "repeated-measures ANOVA, which drops them).",
      m.trials_missing, condition_within ? "condition (seen) x " : "",
      m.trials_missing == 1 ? "" : "s", m.metric, m.participants_with_missing,
      m.participants_with_missing == 1 ? "" : "s",
      m.participants_with_missing == 1 ? "is" : "are",
      m.participants_with_missing == 1 ? "its" : "their");
}

// The strategy's random intercepts: the variance components, the boundary note and lmerTest's
// ranova test of each strategy term (docs/crossed-random-effects.md).
std::string crossed_note(const models::CrossedModelFit& c) {
  std::string o = "Variance components:";
  for (const auto& r : c.random) o += fmt::format(" {} {:.6g}{},", r.name, r.variance, r.at_boundary ? " (at 0)" : "");
  o += fmt::format(" residual {:.6g}.", c.model.variance.residual);
  for (const auto& t : c.term_tests)
    o += fmt::format(" Likelihood-ratio test of {} (lmerTest's ranova, REML): LRT = {:.3f}, chi-squared(1), {}.",
                     t.name, t.lrt, apa_p(t.p));
  if (!c.note.empty()) o += " " + c.note;
  return o;
}

std::string variance_note(const models::MixedModelFit& fit) {
  if (!fit.variance.icc && fit.spec.random_group_slope)
    return "With a random slope of the condition the share of the variance between participants "
           "depends on the condition: no single ICC.";
  if (!fit.variance.icc) {
    return "With a random slope the share of the variance between participants depends on the "
           "iteration: no single ICC.";
  }
  return fmt::format(
      "Variance components: participant {:.6g}, residual {:.6g}; ICC = {:.3f} (the share of the "
      "variance between participants).",
      fit.variance.participant, fit.variance.residual, *fit.variance.icc);
}

// The contrasts A - B per iteration, or the exposure slopes per strategy; needs m.contrasts.
std::string contrasts_note(const ModelOptions& o, const MetricModel& m) {
  const bool kr = o.ddf == models::DdfMethod::kenward_roger;
  const std::string df_name = kr ? "Kenward-Roger" : "Satterthwaite";
  const std::string adj = o.p_adjust == stats::PAdjustMethod::none
                              ? "no p-value adjustment"
                              : fmt::format("p adjusted over the {} {} by {}", m.contrasts.size(),
                                            o.exposure ? "strategies" : "iterations",
                                            std::string(stats::to_string(o.p_adjust)));
  if (o.exposure) {
    return fmt::format(
        "Slope of exposure per strategy: the change of {} per earlier exposure to the same "
        "strategy, with {} df and {}% interval (lmerTest::contest); {}.",
        m.metric, df_name, percent(o.conf_level), adj);
  }
  return fmt::format(
      "Contrasts A - B at each iteration from the model, as emmeans(m, pairwise ~ condition | "
      "iteration, lmer.df = \"{}\"){}; two-sided, {}% intervals; {}. A = {}, B = "
      "{}. "
      "Labels at alpha = {}: A>B / A<B significant; n.s. not significant (a model contrast has "
      "no Bayes factor or TOST here, so none is labelled \u2248).",
      kr ? "kenward-roger" : "satterthwaite", o.trend ? " at each observed iteration of the trend" : "", percent(o.conf_level), adj,
      m.group1, m.group2, io::format_double(o.alpha));
}

std::string emmeans_note(bool kenward_roger) {
  return fmt::format(
      "Estimated marginal means and contrasts as emmeans (lmer.df = \"{}\"): a mean averages "
      "the condition x iteration cells with equal weights; each by-group is one family for "
      "the adjustment; Holm adjusts p and gives Bonferroni intervals (as emmeans); Tukey uses "
      "the studentized range with the family's number of means (exact quantiles; R's qtukey "
      "is precise to about 1e-4); polynomial contrasts use emmeans' integer coefficients.",
      kenward_roger ? "kenward-roger" : "satterthwaite");
}

// --apa: one APA line per ANOVA term, then per contrast (iteration) or slope (strategy).
void add_apa_notes(std::vector<std::string>& notes, const MetricModel& m) {
  for (const auto& t : m.fit.anova) notes.push_back(fmt::format("{}: {}", t.term, anova_apa(t)));
  for (const auto& c : m.contrasts)
    notes.push_back(fmt::format(
        "{}: {}",
        c.iteration ? "iteration " + whole_or_double(*c.iteration) : "exposure slope, " + c.level,
        c.apa));
}

}  // namespace

std::vector<std::string> model_notes(const ModelAnalysis& a, const MetricModel& m) {
  const auto& fit = m.fit;
  const auto& o = a.options;
  const bool kr = o.ddf == models::DdfMethod::kenward_roger;
  std::vector<std::string> notes;
  notes.push_back(model_note(o, m));
  notes.push_back(f_test_note(kr));
  if (o.trend && fit.group_levels.size() > 1)
    notes.push_back(
        "With a linear trend, the condition term tests the difference of the lines at iteration 0 "
        "(the covariate is not centred, as in R); condition:iteration tests the difference of "
        "the slopes.");
  notes.push_back(sample_note(m));
  notes.push_back(missing_trials_note(m, o.condition_within));
  notes.push_back(m.crossed ? crossed_note(*m.crossed) : variance_note(fit));
  if (fit.singular)
    notes.push_back(
        "Singular fit: a variance component is estimated at (or near) zero (lme4: isSingular); "
        "the F tests remain valid but the model may be simpler than specified.");
  if (!m.contrasts.empty()) notes.push_back(contrasts_note(o, m));
  if (!m.emmeans.empty() || !m.emm_contrasts.empty()) notes.push_back(emmeans_note(kr));
  if (o.apa) add_apa_notes(notes, m);
  return notes;
}

namespace {

struct Builder {
  TextTable table;
  std::vector<std::size_t> p_columns;
  void add(std::vector<std::string> cells, const std::vector<std::optional<double>>& p_values) {
    std::vector<std::string> latex(cells.size());
    for (std::size_t j = 0; j < p_columns.size() && j < p_values.size(); ++j)
      latex[p_columns[j]] = format_p(p_values[j], PStyle::latex);
    table.rows.push_back({std::move(cells), false});
    table.latex_cells.push_back(std::move(latex));
  }
};

TextTable anova_table(const MetricModel& m) {
  Builder b;
  b.table.caption =
      fmt::format("Linear mixed model of {}: type III ANOVA ({}'s df)", m.metric,
                  m.fit.spec.ddf == models::DdfMethod::kenward_roger ? "Kenward-Roger"
                                                                    : "Satterthwaite");
  b.table.header = {"Term", "Sum Sq", "Mean Sq", "NumDF", "DenDF", "F", "p"};
  b.table.right_align = {false, true, true, true, true, true, true};
  b.p_columns = {6};
  for (const auto& t : m.fit.anova) {
    if (!t.computed) {
      b.add({t.term, "", "", df_text(t.num_df), "", std::string(kNotComputable), ""}, {});
      continue;
    }
    b.add({t.term, fmt::format("{:.4g}", t.sum_sq), fmt::format("{:.4g}", t.mean_sq),
           df_text(t.num_df), fmt::format("{:.1f}", t.den_df), fmt::format("{:.2f}", t.f),
           format_p(t.p)},
          {t.p});
  }
  return b.table;
}

TextTable random_table(const MetricModel& m) {
  const auto& v = m.fit.variance;
  TextTable t;
  t.caption = fmt::format("Random effects of {}", m.metric);
  t.header = {"Group", "Term", "Variance", "SD", "Corr"};
  t.right_align = {false, false, true, true, true};
  auto row = [&](std::string g, std::string term, double var, std::string corr) {
    t.rows.push_back({{std::move(g), std::move(term), fmt::format("{:.6g}", var),
                       fmt::format("{:.6g}", std::sqrt(var)), std::move(corr)},
                      false});
  };
  row("participant", "(Intercept)", v.participant, "");
  if (v.slope)
    row("participant", m.fit.spec.time, *v.slope,
        v.correlation ? fmt::format("{:.3f}", *v.correlation) : "");
  // (1 + condition | participant): as R prints VarCorr, each dummy's row lists its correlations
  // with the terms above it.
  const std::size_t q = v.group_slopes.size() + 1;
  for (std::size_t k = 1; k < q; ++k) {
    std::string corr;
    for (std::size_t j = 0; j < k; ++j) {
      const double r = v.group_correlations.at(j * q - j * (j + 1) / 2 + (k - j - 1));
      corr += (j ? " " : "") + (std::isnan(r) ? std::string("NaN") : fmt::format("{:.3f}", r));
    }
    row("participant", m.fit.spec.group + m.fit.group_levels.at(k), v.group_slopes[k - 1], corr);
  }
  if (m.crossed)  // the strategy's random intercepts (crossed or nested), as VarCorr lists them
    for (const auto& r : m.crossed->random)
      if (r.term != models::RandomIntercept::participant)
        row(r.name, "(Intercept)", r.variance, r.at_boundary ? "at 0" : "");
  row("Residual", "", v.residual, "");
  return t;
}

TextTable contrast_table(const ModelAnalysis& a, const MetricModel& m) {
  const bool adj = a.options.p_adjust != stats::PAdjustMethod::none;
  const bool slopes = a.options.exposure;
  Builder b;
  const std::string ci = percent(a.options.conf_level) + "% CI";
  if (slopes) {
    b.table.caption = fmt::format("Slope of exposure per strategy ({})", m.metric);
    b.table.header = {"Strategy", "Slope", "SE", "df", ci, "t", "p"};
  } else {
    b.table.caption = fmt::format("{}: {} - {} per iteration (mixed-model contrasts)", m.metric,
                                  m.group1, m.group2);
    b.table.header = {"Iteration", "Estimate", "SE", "df", ci, "t", "p"};
  }
  b.p_columns = {6};
  if (adj) {
    b.table.header.push_back("p (" + std::string(stats::to_string(a.options.p_adjust)) + ")");
    b.p_columns.push_back(7);
  }
  if (!slopes) b.table.header.push_back("Inference");
  b.table.right_align.assign(b.table.header.size(), true);
  b.table.right_align[0] = slopes ? false : true;
  if (!slopes) b.table.right_align.back() = false;
  for (const auto& c : m.contrasts) {
    const auto& t = c.contrast.test;
    std::vector<std::string> cells = {
        slopes ? c.level : whole_or_double(*c.iteration),
        fixed(t.estimate, 4),
        t.computed ? fixed(c.contrast.std_error, 4) : "",
        t.df ? fmt::format("{:.1f}", *t.df) : "",
        t.conf_low ? fmt::format("[{}, {}]", fixed(t.conf_low, 4), fixed(t.conf_high, 4)) : "",
        fixed(t.statistic, 2),
        format_p(t.p_value)};
    if (adj) cells.push_back(format_p(t.p_adjusted));
    if (!slopes) cells.push_back(c.label);
    b.add(std::move(cells), {t.p_value, t.p_adjusted});
  }
  return b.table;
}

TextTable emm_table(const ModelAnalysis& a, const MetricModel& m) {
  Builder b;
  const std::string ci = percent(a.options.conf_level) + "% CI";
  b.table.caption = fmt::format("{}: estimated marginal means ({} df)", m.metric,
                                m.fit.spec.ddf == models::DdfMethod::kenward_roger
                                    ? "Kenward-Roger"
                                    : "Satterthwaite");
  b.table.header = {"Means of", "Level", "EMM", "SE", "df", ci};
  b.table.right_align = {false, false, true, true, true, true};
  for (const auto& t : m.emmeans)
    for (const auto& r : t.rows)
      b.add(std::vector<std::string>{t.term, r.label, fmt::format("{:.4f}", r.estimate),
             r.computed ? fmt::format("{:.4f}", r.std_error) : "",
             r.computed ? fmt::format("{:.1f}", r.df) : "",
             r.computed ? fmt::format("[{:.4f}, {:.4f}]", r.conf_low, r.conf_high) : ""},
            std::vector<std::optional<double>>{});
  return b.table;
}

TextTable emm_contrast_table(const ModelAnalysis& a, const MetricModel& m, const EmmTable& t) {
  Builder b;
  const std::string ci = percent(a.options.conf_level) + "% CI";
  b.table.caption = fmt::format("{}: contrasts {} (p adjustment: {})", m.metric, t.term, t.adjust);
  b.table.header = {"By", "Contrast", "Estimate", "SE", "df", ci, "t", "p"};
  b.table.right_align = {false, false, true, true, true, true, true, true};
  b.p_columns = {7};
  for (const auto& r : t.rows)
    b.add(std::vector<std::string>{r.by, r.label, fmt::format("{:.4f}", r.estimate),
           r.computed ? fmt::format("{:.4f}", r.std_error) : "",
           r.computed ? fmt::format("{:.1f}", r.df) : "",
           r.computed ? fmt::format("[{:.4f}, {:.4f}]", r.conf_low, r.conf_high) : "",
           r.computed ? fmt::format("{:.2f}", r.statistic) : "",
           r.computed ? format_p(r.p_value) : std::string(kNotComputable)},
          {r.computed ? std::optional<double>(r.p_value) : std::nullopt});
  return b.table;
}

constexpr std::string_view kColumns[] = {
    "metric",   "table",     "term",       "group",    "iteration", "level", "contrast",
    "estimate", "std.error", "statistic",  "df",       "NumDF",     "DenDF", "sumsq",
    "meansq",   "p.value",   "p.adjusted", "conf.low", "conf.high", "label", "apa"};

std::size_t column(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kColumns); ++i)
    if (kColumns[i] == name) return i;
  throw std::invalid_argument("model tidy column");
}

struct RecordBuilder {
  Record r = Record(std::size(kColumns));
  RecordBuilder& set(std::string_view c, Cell v) {
    r[column(c)] = std::move(v);
    return *this;
  }
};

// One record per term of the type III ANOVA.
void add_anova_records(std::vector<Record>& out, const ModelAnalysis& a, const MetricModel& m) {
  for (const auto& t : m.fit.anova) {
    RecordBuilder b;
    b.set("metric", Cell::str(m.metric)).set("table", Cell::str("anova"));
    b.set("term", Cell::str(t.term)).set("NumDF", Cell::num(t.num_df));
    if (t.computed) {
      b.set("sumsq", Cell::num(t.sum_sq)).set("meansq", Cell::num(t.mean_sq));
      b.set("DenDF", Cell::num(t.den_df)).set("statistic", Cell::num(t.f));
      b.set("p.value", Cell::num(t.p));
    }
    if (a.options.apa) b.set("apa", Cell::str(anova_apa(t)));
    out.push_back(std::move(b.r));
  }
}

// Variance parameters as broom.mixed names them (var__, cor__), and the ICC when there is one.
void add_random_effect_records(std::vector<Record>& out, const MetricModel& m) {
  const auto& fit = m.fit;
  auto ran = [&](std::string group, std::string term, double value) {
    RecordBuilder b;
    b.set("metric", Cell::str(m.metric)).set("table", Cell::str("ran_pars"));
    b.set("group", Cell::str(std::move(group))).set("term", Cell::str(std::move(term)));
    b.set("estimate", Cell::num(value));
    out.push_back(std::move(b.r));
  };
  ran("participant", "var__(Intercept)", fit.variance.participant);
  if (fit.variance.slope) ran("participant", "var__" + fit.spec.time, *fit.variance.slope);
  if (fit.variance.correlation)
    ran("participant", "cor__(Intercept)." + fit.spec.time, *fit.variance.correlation);
  // (1 + condition | participant), in VarCorr's order: the dummies' variances, then correlations.
  std::vector<std::string> terms = {"(Intercept)"};
  for (std::size_t k = 0; k < fit.variance.group_slopes.size(); ++k) {
    terms.push_back(fit.spec.group + fit.group_levels.at(k + 1));
    ran("participant", "var__" + terms.back(), fit.variance.group_slopes[k]);
  }
  std::size_t c = 0;
  for (std::size_t j = 0; j < terms.size(); ++j)
    for (std::size_t i = j + 1; i < terms.size(); ++i)
      ran("participant", "cor__" + terms[j] + "." + terms[i], fit.variance.group_correlations.at(c++));
  if (m.crossed)
    for (const auto& r : m.crossed->random)
      if (r.term != models::RandomIntercept::participant) ran(r.name, "var__(Intercept)", r.variance);
  ran("Residual", "var__Observation", fit.variance.residual);
  if (fit.variance.icc) ran("participant", "icc", *fit.variance.icc);
}

// Each fixed-effect coefficient, tested as the contrast that picks it out.
void add_fixed_effect_records(std::vector<Record>& out, const ModelAnalysis& a,
                              const MetricModel& m) {
  const auto& fit = m.fit;
  for (std::size_t i = 0; i < fit.coef_names.size(); ++i) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(fit.beta.size());
    L(static_cast<Eigen::Index>(i)) = 1;
    const auto c = models::contrast(fit, L, a.options.conf_level);
    RecordBuilder b;
    b.set("metric", Cell::str(m.metric)).set("table", Cell::str("fixef"));
    b.set("term", Cell::str(fit.coef_names[i])).set("estimate", Cell::num(c.test.estimate));
    if (c.test.computed) b.set("std.error", Cell::num(c.std_error));
    b.set("statistic", Cell::num(c.test.statistic));
    b.set("df", Cell::num(c.test.df)).set("p.value", Cell::num(c.test.p_value));
    b.set("conf.low", Cell::num(c.test.conf_low)).set("conf.high", Cell::num(c.test.conf_high));
    out.push_back(std::move(b.r));
  }
}

// The contrasts A - B per iteration, or the exposure slopes per strategy.
void add_contrast_records(std::vector<Record>& out, const ModelAnalysis& a,
                          const MetricModel& m) {
  for (const auto& c : m.contrasts) {
    const auto& t = c.contrast.test;
    RecordBuilder b;
    b.set("metric", Cell::str(m.metric));
    if (a.options.exposure) {
      b.set("table", Cell::str("slope")).set("term", Cell::str("exposure"));
      b.set("level", Cell::str(c.level));
    } else {
      b.set("table", Cell::str("contrast"));
      b.set("iteration", Cell::num(c.iteration));
      b.set("contrast", Cell::str(m.group1 + " - " + m.group2));
      b.set("label", Cell::str(c.label));
    }
    b.set("estimate", Cell::num(t.estimate));
    if (t.computed) b.set("std.error", Cell::num(c.contrast.std_error));
    b.set("statistic", Cell::num(t.statistic)).set("df", Cell::num(t.df));
    b.set("p.value", Cell::num(t.p_value)).set("p.adjusted", Cell::num(t.p_adjusted));
    b.set("conf.low", Cell::num(t.conf_low)).set("conf.high", Cell::num(t.conf_high));
    if (a.options.apa) b.set("apa", Cell::str(c.apa));
    out.push_back(std::move(b.r));
  }
}

// emmeans: table = emmean (term = the means' factor(s), level) and emm_contrast (term = the
// family, group = its by level, contrast, label = the adjustment; p.value from t, p.adjusted
// with the family's adjustment, conf.low/high adjusted as emmeans).
Record emm_record(const MetricModel& m, const std::string& table, const EmmTable& t,
                  const models::EmmRow& r) {
  RecordBuilder b;
  b.set("metric", Cell::str(m.metric)).set("table", Cell::str(table));
  b.set("term", Cell::str(t.term));
  if (table == "emmean") {
    b.set("level", Cell::str(r.label));
  } else {
    if (!r.by.empty()) b.set("group", Cell::str(r.by));
    b.set("contrast", Cell::str(r.label)).set("label", Cell::str(t.adjust));
  }
  b.set("estimate", Cell::num(r.estimate));
  if (r.computed) {
    b.set("std.error", Cell::num(r.std_error)).set("df", Cell::num(r.df));
    b.set("statistic", Cell::num(r.statistic));
    b.set("p.value", Cell::num(r.p_unadjusted));
    if (table != "emmean") b.set("p.adjusted", Cell::num(r.p_value));
    b.set("conf.low", Cell::num(r.conf_low)).set("conf.high", Cell::num(r.conf_high));
  }
  return std::move(b.r);
}

// Per metric, in this order: ANOVA, variance parameters, fixed effects, contrasts (or slopes),
// estimated marginal means, emmeans contrasts.
std::vector<Record> tidy(const ModelAnalysis& a) {
  std::vector<Record> out;
  for (const auto& m : a.models) {
    add_anova_records(out, a, m);
    add_random_effect_records(out, m);
    add_fixed_effect_records(out, a, m);
    add_contrast_records(out, a, m);
    for (const auto& t : m.emmeans)
      for (const auto& r : t.rows) out.push_back(emm_record(m, "emmean", t, r));
    for (const auto& t : m.emm_contrasts)
      for (const auto& r : t.rows) out.push_back(emm_record(m, "emm_contrast", t, r));
  }
  return out;
}

}  // namespace

std::string render_model(const ModelAnalysis& a, OutputFormat format,
                         const TablePresentation& presentation) {
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    std::vector<std::string_view> cols(std::begin(kColumns), std::end(kColumns));
    if (!a.options.apa) cols.pop_back();
    std::vector<Record> records = tidy(a);
    if (!a.options.apa)
      for (auto& r : records) r.pop_back();
    return format == OutputFormat::csv ? write_csv(cols, records) : write_json(cols, records);
  }
  // Labels: <base>-anova-<metric>, -random-, -contrasts- (or -slopes-); with --label the first
  // ANOVA table gets the label itself and every other table derives from it, so that all stay
  // unique in one paper.
  const std::string base = presentation.label.empty() ? "tab:feint-model" : presentation.label;
  std::vector<std::string> ids;
  std::string out;
  for (const auto& m : a.models) {
    std::string id = latex_label_part(m.metric);
    // Two metric names can reduce to the same fragment ("a_b", "a.b"): number the repeats.
    for (int k = 2; std::find(ids.begin(), ids.end(), id) != ids.end(); ++k)
      id = latex_label_part(m.metric) + "-" + std::to_string(k);
    ids.push_back(id);
    std::vector<TextTable> tables = {anova_table(m), random_table(m)};
    if (!m.contrasts.empty()) tables.push_back(contrast_table(a, m));
    tables[0].latex_label = base + "-anova-" + id;
    tables[1].latex_label = base + "-random-" + id;
    if (tables.size() > 2)
      tables[2].latex_label = base + (a.options.exposure ? "-slopes-" : "-contrasts-") + id;
    if (!m.emmeans.empty()) {
      tables.push_back(emm_table(a, m));
      tables.back().latex_label = base + "-emmeans-" + id;
    }
    for (std::size_t k = 0; k < m.emm_contrasts.size(); ++k) {
      tables.push_back(emm_contrast_table(a, m, m.emm_contrasts[k]));
      tables.back().latex_label = base + "-emm-contrasts-" + id + "-" + std::to_string(k + 1);
    }
    for (auto& t : tables) t.latex_wide = presentation.wide;
    if (&m == &a.models.front()) apply_presentation(tables[0], presentation, tables[0].latex_label);
    tables.back().notes = model_notes(a, m);
    for (const auto& t : tables) {
      if (!out.empty()) out += "\n";
      out += render_table(t, format);
    }
  }
  return out;
}

}  // namespace feint::tables
