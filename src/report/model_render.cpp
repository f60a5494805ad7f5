// `feint model`: scores -> long data -> mixed model per metric -> tables and tidy records.
#include "feint/report/model_render.hpp"

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

namespace feint::report {

namespace {

std::string whole_or_double(double v) { return io::format_double(v); }

std::string fixed(std::optional<double> v, int decimals) { return format_mean(v, decimals); }

std::string df_text(double df) {
  if (df == std::floor(df)) return fmt::format("{}", static_cast<long long>(df));
  return fmt::format("{:.1f}", df);
}

std::string percent(double conf) { return io::format_double(std::round(conf * 1e6) / 1e4); }

}  // namespace

std::string anova_apa(const models::AnovaTerm& a) {
  if (!a.computed) return fmt::format("{}: {}", kNotComputable, a.note);
  std::string f = fmt::format("{:.2f}", a.f);
  return fmt::format("F({}, {:.1f}) = {}, {}", df_text(a.num_df), a.den_df, f, apa_p(a.p));
}

std::vector<std::string> load_strategies(const io::ScoresTable& scores,
                                         const io::ScoresOptions& options,
                                         const std::string& strategy_column) {
  io::CsvReader reader(scores.path);
  const int pc = reader.column(options.participant_column);
  const int ic = reader.column(options.iteration_column);
  const int cc = reader.column(options.condition_column);
  const int sc = reader.column(strategy_column);
  if (sc < 0)
    throw InvalidData(fmt::format("{}: no column '{}': --exposure needs the strategy of each trial",
                                  scores.path, strategy_column));
  std::map<std::tuple<std::string, std::string, long long>, std::string> by_key;
  while (reader.next()) {
    if (pc < 0 || ic < 0) break;
    const std::string participant(io::trim(reader.field(static_cast<std::size_t>(pc))));
    const std::string condition =
        cc >= 0 ? std::string(io::trim(reader.field(static_cast<std::size_t>(cc)))) : "";
    const auto iteration = io::parse_double(io::trim(reader.field(static_cast<std::size_t>(ic))));
    const std::string strategy(io::trim(reader.field(static_cast<std::size_t>(sc))));
    if (strategy.empty())
      throw InvalidData(fmt::format("{}:{}: column '{}': empty strategy (trial {}/{}/{})",
                                    scores.path, reader.line(), strategy_column, participant,
                                    condition, iteration ? whole_or_double(*iteration) : "?"));
    if (iteration) by_key[{participant, condition, static_cast<long long>(*iteration)}] = strategy;
  }
  std::vector<std::string> out;
  out.reserve(scores.records.size());
  for (const auto& r : scores.records) {
    const auto it = by_key.find({r.participant, r.condition, r.iteration});
    if (it == by_key.end())
      throw InvalidData(fmt::format("{}:{}: no strategy for trial {}/{}/{}", scores.path, r.line,
                                    r.participant, r.condition, r.iteration));
    out.push_back(it->second);
  }
  return out;
}

ModelAnalysis build_model_analysis(const io::ScoresTable& scores, const ModelOptions& options,
                                   const std::vector<std::string>* strategy) {
  if (options.random_slope && !options.trend)
    throw UsageError("--random-slope needs --trend (a random slope of the linear trend)");
  if (options.exposure && (options.trend || options.random_slope))
    throw UsageError(
        "--exposure fits its own model (strategy * exposure); drop --trend/--random-slope");
  if (options.exposure && (strategy == nullptr || strategy->size() != scores.records.size()))
    throw std::invalid_argument("build_model_analysis: --exposure needs one strategy per record");
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be in (0, 1)");
  if (!(options.conf_level > 0 && options.conf_level < 1))
    throw UsageError("--conf-level must be in (0, 1)");

  // A participant belongs to one condition (the design's between factor).
  {
    std::map<std::string, const io::ScoreRecord*> first;
    for (const auto& r : scores.records) {
      auto [it, fresh] = first.emplace(r.participant, &r);
      if (!fresh && it->second->condition != r.condition)
        throw InvalidData(fmt::format(
            "{}:{}: participant {} is in condition '{}' but in '{}' on line {}: the condition is "
            "between participants",
            scores.path, r.line, r.participant, r.condition, it->second->condition,
            it->second->line));
    }
  }

  ModelAnalysis a;
  a.options = options;
  a.source = scores.path;
  const std::vector<long long> iterations = scores.iterations();
  std::vector<double> exposure;
  if (options.exposure) {
    std::vector<std::string> participants;
    std::vector<double> its;
    for (const auto& r : scores.records) {
      participants.push_back(r.participant);
      its.push_back(static_cast<double>(r.iteration));
    }
    exposure = models::exposure_counts(participants, its, *strategy);
  }

  for (const auto& metric : options.metrics) {
    const int mi = scores.metric_index(metric);
    if (mi < 0) throw InvalidData(fmt::format("{}: no metric column '{}'", scores.path, metric));
    MetricModel mm;
    mm.metric = metric;
    models::LongData d;
    std::set<long long> iterations_with_value;
    for (std::size_t i = 0; i < scores.records.size(); ++i) {
      const auto& r = scores.records[i];
      const auto& v = r.values[static_cast<std::size_t>(mi)];
      if (!v) continue;
      iterations_with_value.insert(r.iteration);
      d.participant.push_back(r.participant);
      d.group.push_back(options.exposure ? (*strategy)[i] : r.condition);
      d.time.push_back(options.exposure ? exposure[i] : static_cast<double>(r.iteration));
      d.y.push_back(*v);
    }
    if (!options.exposure) {
      for (const long long it : iterations)
        if (!iterations_with_value.count(it))
          throw InvalidData(fmt::format(
              "{}: metric '{}': iteration {} has no value for any participant (every trial of it "
              "is empty)",
              scores.path, metric, it));
    }
    if (d.y.empty())
      throw InvalidData(fmt::format("{}: metric '{}' has no values", scores.path, metric));
    // Missing trials: empty values and absent rows (a participant x iteration without a row).
    // Participants with missing trials stay in the model with the trials they have.
    {
      std::map<std::string, std::size_t> have;
      for (const auto& p : d.participant) ++have[p];
      mm.trials_missing = 0;
      for (const auto& [p, n] : have) {
        if (n < iterations.size()) {
          ++mm.participants_with_missing;
          mm.trials_missing += iterations.size() - n;
        }
      }
    }

    models::ModelSpec spec;
    spec.response = metric;
    spec.group = options.exposure ? "strategy" : "condition";
    spec.time = options.exposure ? "exposure" : "iteration";
    spec.time_scale =
        options.exposure || options.trend ? models::TimeScale::linear : models::TimeScale::factor;
    spec.random_slope = options.random_slope;
    spec.ddf = options.ddf;
    try {
      mm.fit = models::fit_mixed_model(d, spec, !options.exposure);
    } catch (const InvalidData& e) {
      throw InvalidData(fmt::format("{}: {}", scores.path, e.what()));  // name the file
    }
    const auto& fit = mm.fit;
    const bool one_group = fit.group_levels.size() < 2;
    const std::string rhs = one_group ? spec.time : fmt::format("{} * {}", spec.group, spec.time);
    mm.formula = fmt::format("{} ~ {} + ({} | participant)", metric, rhs,
                             options.random_slope ? "1 + iteration" : "1");

    // Participants per condition (or in all, with exposure).
    if (!options.exposure) {
      std::map<std::string, std::set<std::string>> per;
      for (std::size_t i = 0; i < d.y.size(); ++i) per[d.group[i]].insert(d.participant[i]);
      for (const auto& g : fit.group_levels)
        mm.participants_per_group.emplace_back(g, per[g].size());
    }

    // Contrasts A - B per iteration, or exposure slopes per strategy.
    std::vector<models::Contrast> cs;
    if (options.exposure) {
      for (std::size_t k = 0; k < fit.group_levels.size(); ++k) {
        ModelContrast c;
        c.level = fit.group_levels[k];
        c.contrast =
            models::contrast(fit, fit.cell_row(k, 1.0) - fit.cell_row(k, 0.0), options.conf_level);
        mm.contrasts.push_back(std::move(c));
      }
    } else if (!one_group) {
      std::size_t ia = 0, ib = 1;
      if (options.compare) {
        auto find = [&](const std::string& name) {
          const auto it = std::find(fit.group_levels.begin(), fit.group_levels.end(), name);
          if (it == fit.group_levels.end())
            throw InvalidData(
                fmt::format("{}: --compare: no condition '{}' in the data", scores.path, name));
          return static_cast<std::size_t>(it - fit.group_levels.begin());
        };
        ia = find(options.compare->first);
        ib = find(options.compare->second);
        if (ia == ib) throw UsageError("--compare needs two different conditions");
      }
      mm.group1 = fit.group_levels[ia];
      mm.group2 = fit.group_levels[ib];
      for (const double t : fit.time_levels) {
        ModelContrast c;
        c.iteration = t;
        c.contrast =
            models::contrast(fit, fit.cell_row(ia, t) - fit.cell_row(ib, t), options.conf_level);
        mm.contrasts.push_back(std::move(c));
      }
    }
    if (options.emmeans || !options.contrast_families.empty()) {
      if (options.exposure || options.trend)
        throw UsageError(
            "--emmeans and --contrasts need iteration as a factor (not --trend or --exposure)");
      if (options.emmeans)
        for (const auto term :
             {models::EmmTerm::cells, models::EmmTerm::condition, models::EmmTerm::iteration}) {
          if (term != models::EmmTerm::iteration && one_group) continue;
          mm.emmeans.push_back(
              {models::to_string(term), "", models::estimated_means(fit, term, options.conf_level)});
        }
      for (const auto family : options.contrast_families) {
        const bool is_poly = family == models::EmmFamily::poly_iteration ||
                             family == models::EmmFamily::poly_in_condition;
        const bool by_condition = family == models::EmmFamily::pairwise_condition ||
                                  family == models::EmmFamily::condition_at_iteration;
        if (one_group && by_condition) continue;  // one condition: nothing to contrast
        const models::EmmAdjust adj =
            options.adjust ? *options.adjust
                           : (is_poly ? models::EmmAdjust::none : models::EmmAdjust::tukey);
        mm.emm_contrasts.push_back({models::to_string(family), models::to_string(adj),
                                    models::emm_contrasts(fit, family, adj, options.conf_level)});
      }
    }
    std::vector<std::optional<double>> ps;
    for (const auto& c : mm.contrasts) ps.push_back(c.contrast.test.p_value);
    const auto adj = stats::p_adjust(ps, options.p_adjust);
    for (std::size_t i = 0; i < mm.contrasts.size(); ++i) {
      auto& c = mm.contrasts[i];
      if (options.p_adjust != stats::PAdjustMethod::none) c.contrast.test.p_adjusted = adj[i];
      if (!options.exposure) c.label = two_sample_label(c.contrast.test, options.alpha);
      if (options.exposure && c.contrast.test.computed) {
        const auto& t = c.contrast.test;
        c.apa = fmt::format("b = {:.4f}, {}% CI [{:.4f}, {:.4f}], t({:.1f}) = {:.2f}, {}",
                            *t.estimate, percent(options.conf_level), *t.conf_low, *t.conf_high,
                            *t.df, *t.statistic, apa_p(*t.p_value));
        if (t.p_adjusted) c.apa += ", adjusted " + apa_p(*t.p_adjusted);
      } else {
        c.apa = apa_string(c.contrast.test);
      }
    }
    mm.data = std::move(d);
    a.models.push_back(std::move(mm));
  }
  return a;
}

std::vector<std::string> model_notes(const ModelAnalysis& a, const MetricModel& m) {
  const auto& fit = m.fit;
  const auto& o = a.options;
  std::vector<std::string> notes;
  const std::string time_text =
      o.exposure ? "exposure = how many times the participant had already seen the trial's "
                   "strategy (0 at the first exposure), as a linear covariate"
      : o.trend  ? "iteration as a linear trend"
                 : "iteration as a factor";
  notes.push_back(fmt::format(
      "Linear mixed model {} ({}; R's treatment coding), fitted by REML as lme4::lmer (REML "
      "criterion {:.4f}).",
      m.formula, time_text, fit.reml_criterion));
  const bool kr = o.ddf == models::DdfMethod::kenward_roger;
  notes.push_back(
      kr ? "Type III F tests with Kenward-Roger's adjusted covariance, denominator degrees of "
           "freedom and F scaling (Kenward & Roger 1997), as lmerTest::anova(m, ddf = "
           "\"Kenward-Roger\") / pbkrtest::KRmodcomp; Sum Sq and Mean Sq are lmerTest's "
           "(unscaled Wald F times sigma^2)."
         : "Type III F tests with Satterthwaite's denominator degrees of freedom, as "
           "lmerTest::anova(m) (its type-III hypotheses do not depend on the contrast coding).");
  const std::string df_name = kr ? "Kenward-Roger" : "Satterthwaite";
  if (o.trend && fit.group_levels.size() > 1)
    notes.push_back(
        "With a linear trend, the condition term tests the difference of the lines at iteration 0 "
        "(the covariate is not centred, as in R); condition:iteration tests the difference of "
        "the slopes.");
  std::string groups;
  for (const auto& [g, n] : m.participants_per_group)
    if (m.participants_per_group.size() > 1)
      groups += fmt::format("{}{} in {}", groups.empty() ? "" : ", ", n, g.empty() ? "all" : g);
  notes.push_back(fmt::format("{} participants{}, {} trials.", fit.participants.size(),
                              groups.empty() ? "" : " (" + groups + ")", fit.n_obs));
  if (m.trials_missing > 0) {
    notes.push_back(fmt::format(
        "{} participant x iteration trial{} without a value of {} (empty or absent); the {} "
        "participant{} with missing trials {} kept with {} other trials (unlike the "
        "repeated-measures ANOVA, which drops them).",
        m.trials_missing, m.trials_missing == 1 ? "" : "s", m.metric, m.participants_with_missing,
        m.participants_with_missing == 1 ? "" : "s",
        m.participants_with_missing == 1 ? "is" : "are",
        m.participants_with_missing == 1 ? "its" : "their"));
  } else {
    notes.push_back("No missing trials.");
  }
  if (fit.variance.icc) {
    notes.push_back(fmt::format(
        "Variance components: participant {:.6g}, residual {:.6g}; ICC = {:.3f} (the share of the "
        "variance between participants).",
        fit.variance.participant, fit.variance.residual, *fit.variance.icc));
  } else {
    notes.push_back(
        "With a random slope the share of the variance between participants depends on the "
        "iteration: no single ICC.");
  }
  if (fit.singular)
    notes.push_back(
        "Singular fit: a variance component is estimated at (or near) zero (lme4: isSingular); "
        "the F tests remain valid but the model may be simpler than specified.");
  if (!m.contrasts.empty()) {
    const std::string adj = o.p_adjust == stats::PAdjustMethod::none
                                ? "no p-value adjustment"
                                : fmt::format("p adjusted over the {} {} by {}", m.contrasts.size(),
                                              o.exposure ? "strategies" : "iterations",
                                              std::string(stats::to_string(o.p_adjust)));
    if (o.exposure) {
      notes.push_back(fmt::format(
          "Slope of exposure per strategy: the change of {} per earlier exposure to the same "
          "strategy, with {} df and {}% interval (lmerTest::contest); {}.",
          m.metric, df_name, percent(o.conf_level), adj));
    } else {
      notes.push_back(fmt::format(
          "Contrasts A - B at each iteration from the model, as emmeans(m, pairwise ~ condition | "
          "iteration, lmer.df = \"{}\"){}; two-sided, {}% intervals; {}. A = {}, B = "
          "{}. "
          "Labels at alpha = {}: A>B / A<B significant, A\u2248B not significantly different.",
          kr ? "kenward-roger" : "satterthwaite", o.trend ? " at each observed iteration of the trend" : "", percent(o.conf_level), adj,
          m.group1, m.group2, io::format_double(o.alpha)));
    }
  }
  if (!m.emmeans.empty() || !m.emm_contrasts.empty())
    notes.push_back(fmt::format(
        "Estimated marginal means and contrasts as emmeans (lmer.df = \"{}\"): a mean averages "
        "the condition x iteration cells with equal weights; each by-group is one family for "
        "the adjustment; Holm adjusts p and gives Bonferroni intervals (as emmeans); Tukey uses "
        "the studentized range with the family's number of means (exact quantiles; R's qtukey "
        "is precise to about 1e-4); polynomial contrasts use emmeans' integer coefficients.",
        kr ? "kenward-roger" : "satterthwaite"));
  if (o.apa) {
    for (const auto& t : fit.anova) notes.push_back(fmt::format("{}: {}", t.term, anova_apa(t)));
    for (const auto& c : m.contrasts)
      notes.push_back(fmt::format(
          "{}: {}",
          c.iteration ? "iteration " + whole_or_double(*c.iteration) : "exposure slope, " + c.level,
          c.apa));
  }
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

std::vector<Record> tidy(const ModelAnalysis& a) {
  std::vector<Record> out;
  for (const auto& m : a.models) {
    const auto& fit = m.fit;
    for (const auto& t : fit.anova) {
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
    ran("Residual", "var__Observation", fit.variance.residual);
    if (fit.variance.icc) ran("participant", "icc", *fit.variance.icc);
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
    // emmeans: table = emmean (term = the means' factor(s), level) and emm_contrast (term = the
    // family, group = its by level, contrast, label = the adjustment; p.value from t, p.adjusted
    // with the family's adjustment, conf.low/high adjusted as emmeans).
    auto emm = [&](const std::string& table, const EmmTable& t, const models::EmmRow& r) {
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
      out.push_back(std::move(b.r));
    };
    for (const auto& t : m.emmeans)
      for (const auto& r : t.rows) emm("emmean", t, r);
    for (const auto& t : m.emm_contrasts)
      for (const auto& r : t.rows) emm("emm_contrast", t, r);
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

void validate(const ModelOptions& o) {
  if ((o.emmeans || !o.contrast_families.empty()) && (o.trend || o.exposure))
    throw UsageError("--emmeans and --contrasts need iteration as a factor (drop --trend/--exposure)");
  if (o.exposure && o.compare) throw UsageError("--compare does not apply to --exposure");
  if (o.random_slope && !o.trend)
    throw UsageError("--random-slope needs --trend (a random slope of the linear trend)");
  if (o.exposure && (o.trend || o.random_slope))
    throw UsageError(
        "--exposure fits its own model (strategy * exposure); drop --trend/--random-slope");

}

}  // namespace feint::report
