// The study's figures: data from upstream results, the drawing description, the alt text.
#include "feint/plot/figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/report/writers.hpp"

namespace feint::plot {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double value(const std::optional<double>& v) { return v ? *v : kNaN; }

// A label says the test found a difference: M>R, M<R, A>B, A<B.
bool differs(const report::TidyRow& row) {
  return row.label.find('>') != std::string::npos || row.label.find('<') != std::string::npos;
}

std::string p_threshold(double alpha) {
  std::string s = fmt::format("{:g}", alpha);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);  // APA: no leading zero
  return s;
}

std::string adjust_words(const std::string& p_adjust) {
  return p_adjust.empty() || p_adjust == "none" ? "" : fmt::format(", {}", p_adjust);
}

// Iteration ticks: 1 and round numbers up to the last iteration.
std::vector<double> iteration_ticks(long long first, long long last) {
  std::vector<double> t = detail::nice_ticks(static_cast<double>(first), static_cast<double>(last));
  if (t.size() >= 2 && first >= 0 && t.front() - static_cast<double>(first) >= (t[1] - t[0]) / 2) {
    t.insert(t.begin(), static_cast<double>(first));
  }
  return t;
}

std::string condition_name(const std::string& c) { return c.empty() ? "all participants" : c; }

// The metric's range as axis bounds (only the finite ends).
void bound(Axis& a, const MetricRange& r) {
  if (std::isfinite(r.lo)) a.bound_min = r.lo;
  if (std::isfinite(r.hi)) a.bound_max = r.hi;
}

double clip(double v, const MetricRange& r) {
  return std::isnan(v) ? v : std::clamp(v, r.lo, r.hi);
}

std::string number(double v) {
  if (!std::isfinite(v)) return "NA";
  if (std::fabs(v) < 0.005) v = 0;  // no "-0.00"
  return fmt::format("{:.2f}", v);
}

// "A and B", "A, B and C".
std::string and_list(const std::vector<std::string>& names) {
  if (names.empty()) return "";
  if (names.size() == 1) return names[0];
  std::string s;
  for (std::size_t i = 0; i + 1 < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s + " and " + names.back();
}

std::vector<std::string> condition_names(const std::vector<std::string>& cs) {
  std::vector<std::string> out;
  for (const auto& c : cs) out.push_back(condition_name(c));
  return out;
}

std::string capitalise(std::string s) {
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

Line band_line(const Style& style, const std::vector<MetricPoint>& points, const MetricRange& r) {
  Line l;
  l.style = style;
  l.band = true;
  for (const auto& pt : points) {
    l.x.push_back(static_cast<double>(pt.iteration));
    l.y.push_back(pt.mean);
    l.lo.push_back(clip(pt.conf_low, r));
    l.hi.push_back(clip(pt.conf_high, r));
    l.filled.push_back(pt.differs);
  }
  return l;
}

void iteration_axis(Axis& a, long long first, long long last) {
  a.label = "Iteration";
  if (first <= last) {
    a.min = static_cast<double>(first) - 0.5;
    a.max = static_cast<double>(last) + 0.5;
    a.ticks = iteration_ticks(first, last);
  }
}

}  // namespace

MetricRange metric_range(const std::string& metric) {
  if (metric == "error" || metric == "confusion") return {0.0, 1.0};
  return {};
}

std::string metric_axis_label(const std::string& metric) {
  if (metric == "error") return "Error (pad units)";
  if (metric == "confusion") return "Confusion (0\u20131)";
  std::string s = metric;
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

Style style_of_condition(const std::vector<std::string>& conditions, const std::string& c) {
  std::vector<std::string> sorted = conditions;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), c);
  return condition_style(static_cast<std::size_t>(it - sorted.begin()));
}

// ---------------------------------------------------------------------------------------------

MetricFigureData metric_figure_data(const report::Table1& one_sample,
                                    const report::Table1* comparison, const std::string& metric) {
  return metric_figure_data(one_sample, comparison, metric, metric_range(metric));
}

MetricFigureData metric_figure_data(const report::Table1& one_sample,
                                    const report::Table1* comparison, const std::string& metric,
                                    MetricRange range) {
  MetricFigureData d;
  d.metric = metric;
  d.range = range;
  const auto& ms = one_sample.options.metrics;
  const auto it =
      std::find_if(ms.begin(), ms.end(), [&](const auto& m) { return m.column == metric; });
  if (it == ms.end()) {
    throw InvalidData(fmt::format("figure '{}': not one of the table's metrics", metric));
  }
  const std::size_t m = static_cast<std::size_t>(it - ms.begin());
  d.reference = it->reference;
  d.conf_level = one_sample.options.test.conf_level;
  d.alpha = one_sample.options.alpha;
  d.p_adjust = std::string(stats::to_string(one_sample.options.p_adjust));
  for (const auto& block : one_sample.blocks) {
    MetricSeries s;
    s.condition = block.group1;
    for (std::size_t i = 0; i < block.iterations.size(); ++i) {
      const report::TidyRow& row = one_sample.rows[block.cells[i][m].difference_row];
      MetricPoint p;
      p.iteration = block.iterations[i];
      p.mean = value(row.result.mean1);
      p.conf_low = value(row.result.conf_low);
      p.conf_high = value(row.result.conf_high);
      p.differs = differs(row);
      s.points.push_back(p);
    }
    d.series.push_back(std::move(s));
  }
  if (comparison != nullptr) {
    const auto& cm = comparison->options.metrics;
    const auto ct =
        std::find_if(cm.begin(), cm.end(), [&](const auto& x) { return x.column == metric; });
    if (ct != cm.end() && !comparison->blocks.empty()) {
      const std::size_t k = static_cast<std::size_t>(ct - cm.begin());
      const auto& block = comparison->blocks.front();
      d.group1 = block.group1;
      d.group2 = block.group2;
      for (std::size_t i = 0; i < block.iterations.size(); ++i) {
        if (differs(comparison->rows[block.cells[i][k].difference_row])) {
          d.marked.push_back(block.iterations[i]);
        }
      }
    }
  }
  return d;
}

namespace {

std::vector<std::string> series_conditions(const MetricFigureData& d) {
  std::vector<std::string> cs;
  for (const auto& s : d.series) cs.push_back(s.condition);
  return cs;
}

std::pair<long long, long long> iteration_span(const MetricFigureData& d) {
  long long first = std::numeric_limits<long long>::max(), last = 0;
  for (const auto& s : d.series) {
    for (const auto& pt : s.points) {
      first = std::min(first, pt.iteration);
      last = std::max(last, pt.iteration);
    }
  }
  return {first, last};
}

}  // namespace

Figure metric_figure(const MetricFigureData& d) {
  Figure f;
  Panel p;
  const auto conditions = series_conditions(d);
  for (const auto& s : d.series) {
    Line l = band_line(style_of_condition(conditions, s.condition), s.points, d.range);
    l.label = condition_name(s.condition);
    f.legend.push_back({LegendEntry::Kind::band, l.label, l.style, false});
    p.lines.push_back(std::move(l));
  }
  const std::string adjust = adjust_words(d.p_adjust);
  f.legend.push_back({LegendEntry::Kind::marker,
                      fmt::format("hollow: \u2248 R (p \u2265 {}{})", p_threshold(d.alpha), adjust),
                      Style{Colour{0.3, 0.3, 0.3}, Dash::solid, Marker::circle}, true});
  if (!d.group1.empty()) {
    f.legend.push_back(
        {LegendEntry::Kind::asterisk,
         fmt::format("{} \u2260 {} (p < {}{})", d.group1, d.group2, p_threshold(d.alpha), adjust),
         {},
         false});
    for (long long it : d.marked) p.marks.push_back(static_cast<double>(it));
  }
  p.refs.push_back({d.reference, false, fmt::format("R = {:g}", d.reference)});
  const auto [first, last] = iteration_span(d);
  iteration_axis(p.x, first, last);
  bound(p.y, d.range);
  p.y.label = fmt::format("{} \u00b1 {:g}% CI", metric_axis_label(d.metric), d.conf_level * 100);
  f.panels.push_back(std::move(p));
  return f;
}

std::string alt_text(const MetricFigureData& d) {
  const auto [first, last] = iteration_span(d);
  if (first > last) return fmt::format("Line chart of the mean {}: no data.", d.metric);
  std::string s = fmt::format(
      "Line chart of the mean {} per iteration ({} to {}) for {}, each with its {:g}% confidence "
      "band, against the reference {:g}.",
      d.metric, first, last, and_list(condition_names(series_conditions(d))), d.conf_level * 100,
      d.reference);
  std::vector<std::string> parts;
  for (const auto& series : d.series) {
    double sum = 0;
    std::size_t n = 0, below = 0, above = 0;
    for (const auto& pt : series.points) {
      if (!std::isfinite(pt.mean)) continue;
      sum += pt.mean;
      ++n;
      if (pt.differs && pt.mean < d.reference) ++below;
      if (pt.differs && pt.mean > d.reference) ++above;
    }
    parts.push_back(fmt::format("{} averages {} ({} iterations below and {} above the reference)",
                                condition_name(series.condition),
                                number(n ? sum / static_cast<double>(n) : kNaN), below, above));
  }
  s += fmt::format(" {}", capitalise(and_list(parts)));
  if (!d.group1.empty()) {
    s += fmt::format("; {} and {} differ at {} iteration{}", d.group1, d.group2, d.marked.size(),
                     d.marked.size() == 1 ? "" : "s");
  }
  return s + ".";
}

// ---------------------------------------------------------------------------------------------

ParticipantsData participants_data(const io::ScoresTable& scores, const std::string& metric,
                                   const report::Table1* one_sample) {
  return participants_data(scores, metric, one_sample, metric_range(metric));
}

ParticipantsData participants_data(const io::ScoresTable& scores, const std::string& metric,
                                   const report::Table1* one_sample, MetricRange range) {
  const int m = scores.metric_index(metric);
  if (m < 0) throw InvalidData(fmt::format("figure participants: metric '{}' not loaded", metric));
  ParticipantsData d;
  d.metric = metric;
  d.range = range;
  std::optional<MetricFigureData> means;
  if (one_sample != nullptr) {
    means = metric_figure_data(*one_sample, nullptr, metric, range);
    d.reference = means->reference;
    d.conf_level = means->conf_level;
  }
  for (const auto& c : scores.conditions()) {
    ParticipantsPanel panel;
    panel.condition = c;
    std::map<std::string, std::vector<std::pair<long long, double>>> rows;
    std::vector<std::string> order;
    for (const auto& r : scores.records) {
      if (r.condition != c) continue;
      auto [pos, fresh] = rows.try_emplace(r.participant);
      if (fresh) order.push_back(r.participant);
      pos->second.emplace_back(r.iteration, value(r.values[static_cast<std::size_t>(m)]));
    }
    for (const auto& who : order) {
      auto pts = rows[who];
      std::sort(pts.begin(), pts.end());
      ParticipantLine line;
      line.participant = who;
      for (const auto& [it, v] : pts) {
        line.iterations.push_back(it);
        line.values.push_back(v);
      }
      panel.participants.push_back(std::move(line));
    }
    if (means) {
      for (const auto& s : means->series) {
        if (s.condition == c) panel.means = s.points;
      }
    }
    d.panels.push_back(std::move(panel));
  }
  return d;
}

Figure participants_figure(const io::ScoresTable& scores, const std::string& metric,
                           const report::Table1* one_sample) {
  return participants_figure(participants_data(scores, metric, one_sample));
}

Figure participants_figure(const ParticipantsData& d) {
  Figure f;
  std::vector<std::string> conditions;
  for (const auto& p : d.panels) conditions.push_back(p.condition);
  long long first = std::numeric_limits<long long>::max(), last = 0;
  for (const auto& panel : d.panels) {
    Panel p;
    p.title = condition_name(panel.condition);
    const Style style = style_of_condition(conditions, panel.condition);
    for (const auto& who : panel.participants) {
      // Faint, thin, in the condition's colour: the crowd, not the message.
      Line l;
      l.style = Style{style.colour, Dash::solid, Marker::none};
      l.opacity = std::clamp(4.0 / static_cast<double>(panel.participants.size()), 0.12, 0.4);
      l.line_width = 0.45;
      long long prev = std::numeric_limits<long long>::min();
      for (std::size_t i = 0; i < who.iterations.size(); ++i) {
        const long long it = who.iterations[i];
        if (prev != std::numeric_limits<long long>::min() && it != prev + 1) {
          l.x.push_back(static_cast<double>(prev) + 0.5);  // a skipped iteration breaks the line
          l.y.push_back(kNaN);
        }
        l.x.push_back(static_cast<double>(it));
        l.y.push_back(who.values[i]);
        first = std::min(first, it);
        last = std::max(last, it);
        prev = it;
      }
      p.lines.push_back(std::move(l));
    }
    if (!panel.means.empty()) {
      Line l = band_line(style, panel.means, d.range);
      l.line_width = 1.8;
      l.halo = true;
      l.filled.clear();
      l.style.marker = Marker::none;
      p.lines.push_back(std::move(l));
    }
    if (d.reference) p.refs.push_back({*d.reference, false, fmt::format("R = {:g}", *d.reference)});
    p.y.label = metric_axis_label(d.metric);
    bound(p.y, d.range);
    f.panels.push_back(std::move(p));
  }
  for (auto& p : f.panels) iteration_axis(p.x, first, last);
  f.shared_axes = true;
  f.max_columns_narrow = 1;  // one panel per row in a column: the lines need the width
  for (const auto& c : conditions) {
    Style s = style_of_condition(conditions, c);
    s.marker = Marker::none;
    if (d.reference || std::any_of(d.panels.begin(), d.panels.end(),
                                   [](const ParticipantsPanel& p) { return !p.means.empty(); })) {
      f.legend.push_back(
          {LegendEntry::Kind::band,
           fmt::format("{}: mean \u00b1 {:g}% CI", condition_name(c), d.conf_level * 100), s,
           false});
    }
  }
  f.legend.push_back({LegendEntry::Kind::line, "faint: one participant",
                      Style{Colour{0.75, 0.75, 0.75}, Dash::solid, Marker::none}, false});
  f.columns = 2;
  return f;
}

std::string alt_text(const ParticipantsData& d) {
  std::vector<std::string> parts, conditions;
  for (const auto& p : d.panels) {
    conditions.push_back(condition_name(p.condition));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& who : p.participants) {
      for (double v : who.values) {
        if (!std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    parts.push_back(fmt::format("{} participants in {} (values {} to {})", p.participants.size(),
                                condition_name(p.condition), number(lo), number(hi)));
  }
  std::string s = fmt::format(
      "Each participant's {} per iteration as a faint line, one panel per condition ({}), with "
      "the condition's mean{} on top.",
      d.metric, and_list(conditions),
      d.reference ? fmt::format(" and its {:g}% confidence band", d.conf_level * 100) : "");
  return s + (parts.empty() ? std::string(" No condition.") : " " + and_list(parts) + ".");
}

// ---------------------------------------------------------------------------------------------

Figure exposure_figure(const metrics::ExposureTrend& d) {
  return exposure_figure(d, metric_range(d.metric));
}

Figure exposure_figure(const metrics::ExposureTrend& d, MetricRange range, std::size_t min_trials) {
  Figure f;
  long long max_exposure = 1;
  for (const auto& st : d.strategies) {
    for (const auto& se : st.series) {
      for (const auto& pt : se.points) {
        if (pt.n >= min_trials) max_exposure = std::max(max_exposure, pt.exposure);
      }
      if (se.fit.fitted && !se.fit.exposure.empty()) {
        max_exposure = std::max(max_exposure, static_cast<long long>(se.fit.exposure.back()));
      }
    }
  }
  const std::size_t k = d.conditions.size();
  for (const auto& st : d.strategies) {
    Panel p;
    p.title = st.strategy;
    for (std::size_t c = 0; c < st.series.size(); ++c) {
      const auto& se = st.series[c];
      const Style style = style_of_condition(d.conditions, se.condition);
      if (se.fit.fitted) {  // the fitted slope with its band, below the means
        Line fit;
        fit.style = Style{style.colour, style.dash, Marker::none};
        fit.band = true;
        fit.line_width = 1.2;
        fit.x = se.fit.exposure;
        fit.y = se.fit.fit;
        for (std::size_t i = 0; i < se.fit.low.size(); ++i) {
          fit.lo.push_back(clip(se.fit.low[i], range));
          fit.hi.push_back(clip(se.fit.high[i], range));
        }
        p.lines.push_back(std::move(fit));
      }
      // Means with their intervals, dodged sideways so that the conditions' bars do not overlap.
      Line means;
      means.style = style;
      means.connect = false;
      means.error_bars = ErrorBars::vertical;
      const double dodge = k <= 1 ? 0.0 : 0.16 * (static_cast<double>(c) / (k - 1) - 0.5);
      for (const auto& pt : se.points) {
        if (pt.n < min_trials) continue;  // a mean of one or two trials is noise
        means.x.push_back(static_cast<double>(pt.exposure) + dodge);
        means.y.push_back(pt.mean);
        means.lo.push_back(clip(pt.conf_low, range));
        means.hi.push_back(clip(pt.conf_high, range));
      }
      p.lines.push_back(std::move(means));
    }
    p.x.label = "Exposure (times seen)";
    p.x.min = 0.5;
    p.x.max = static_cast<double>(max_exposure) + 0.5;
    p.x.ticks = iteration_ticks(1, max_exposure);
    p.y.label = metric_axis_label(d.metric);  // short: small panels; the legend says CI
    bound(p.y, range);
    f.panels.push_back(std::move(p));
  }
  for (const auto& c : d.conditions) {
    f.legend.push_back(
        {LegendEntry::Kind::band,
         fmt::format("{}: fitted line, mean ± {:g}% CI", condition_name(c), d.conf_level * 100),
         style_of_condition(d.conditions, c), false});
  }
  if (min_trials > 1) {
    f.legend.push_back(
        {LegendEntry::Kind::text, fmt::format("(means of ≥ {} trials)", min_trials), {}, false});
  }
  const std::size_t n = std::max<std::size_t>(1, d.strategies.size());
  f.columns = std::min<std::size_t>(4, n);  // one row across a page
  f.max_columns_narrow = 2;                 // 2 x 2 in a column
  f.shared_axes = true;
  f.aspect = 0.95;
  return f;
}

std::string alt_text(const metrics::ExposureTrend& d) {
  std::vector<std::string> strategies;
  const metrics::ExposureSeries* lo = nullptr;
  const metrics::ExposureSeries* hi = nullptr;
  std::string lo_name, hi_name;
  for (const auto& st : d.strategies) {
    strategies.push_back(st.strategy);
    for (const auto& se : st.series) {
      if (!se.fit.fitted) continue;
      if (lo == nullptr || se.fit.slope < lo->fit.slope) {
        lo = &se;
        lo_name = st.strategy;
      }
      if (hi == nullptr || se.fit.slope > hi->fit.slope) {
        hi = &se;
        hi_name = st.strategy;
      }
    }
  }
  std::string s = fmt::format(
      "Mean {} against the number of times the participant had seen the strategy, one panel per "
      "strategy ({}), for {}, with each condition's fitted line and its {:g}% band.",
      d.metric, and_list(strategies), and_list(condition_names(d.conditions)), d.conf_level * 100);
  if (lo != nullptr) {
    s += fmt::format(" The fitted slopes per exposure range from {} ({}, {}) to {} ({}, {}).",
                     number(lo->fit.slope), lo_name, condition_name(lo->condition),
                     number(hi->fit.slope), hi_name, condition_name(hi->condition));
  }
  return s;
}

// ---------------------------------------------------------------------------------------------

Figure model_fit_figure(const ModelFitFigureData& d) {
  Figure f;
  Panel p;
  const auto conditions = series_conditions(d.means);
  const MetricRange& range = d.means.range;
  for (const auto& t : d.trend) {
    const Style style = style_of_condition(conditions, t.group);
    Line fit;
    fit.style = Style{style.colour, style.dash, Marker::none};
    fit.band = true;
    fit.line_width = 1.3;
    for (const auto& pt : t.points) {
      fit.x.push_back(pt.time);
      fit.y.push_back(pt.fit);
      fit.lo.push_back(clip(pt.low, range));
      fit.hi.push_back(clip(pt.high, range));
    }
    p.lines.push_back(std::move(fit));
  }
  const std::size_t k = d.means.series.size();
  for (std::size_t c = 0; c < k; ++c) {
    const auto& s = d.means.series[c];
    Line l;
    l.style = style_of_condition(conditions, s.condition);
    l.connect = false;
    l.error_bars = ErrorBars::vertical;
    // Dodged sideways so that the conditions' intervals do not overlap.
    const double dodge = k <= 1 ? 0.0 : 0.3 * (static_cast<double>(c) / (k - 1) - 0.5);
    for (const auto& pt : s.points) {
      l.x.push_back(static_cast<double>(pt.iteration) + dodge);
      l.y.push_back(pt.mean);
      l.lo.push_back(clip(pt.conf_low, range));
      l.hi.push_back(clip(pt.conf_high, range));
    }
    l.opacity = 0.8;
    p.lines.push_back(std::move(l));
  }
  for (const auto& c : conditions) {
    const Style s = style_of_condition(conditions, c);
    f.legend.push_back({LegendEntry::Kind::band, fmt::format("{}: model fit", condition_name(c)),
                        Style{s.colour, s.dash, Marker::none}, false});
  }
  f.legend.push_back({LegendEntry::Kind::marker,
                      fmt::format("observed mean ± {:g}% CI", d.means.conf_level * 100),
                      Style{Colour{0.3, 0.3, 0.3}, Dash::solid, Marker::circle}, false});
  p.refs.push_back({d.means.reference, false, fmt::format("R = {:g}", d.means.reference)});
  const auto [first, last] = iteration_span(d.means);
  iteration_axis(p.x, first, last);
  bound(p.y, range);
  p.y.label = metric_axis_label(d.means.metric);
  if (!d.model.empty()) p.note = d.model;
  f.panels.push_back(std::move(p));
  return f;
}

std::string alt_text(const ModelFitFigureData& d) {
  std::vector<std::string> parts;
  for (const auto& t : d.trend) {
    if (t.points.empty()) continue;
    parts.push_back(fmt::format("{} from {} to {}", condition_name(t.group),
                                number(t.points.front().fit), number(t.points.back().fit)));
  }
  if (parts.empty()) return fmt::format("The mixed model's fitted {}: no fit.", d.means.metric);
  return fmt::format(
      "The mixed model's fitted {} per iteration{} with its {:g}% band for {}, over the observed "
      "means with their intervals. The fit goes {}.",
      d.means.metric, d.model.empty() ? "" : " (" + d.model + ")", d.means.conf_level * 100,
      and_list(condition_names(series_conditions(d.means))), and_list(parts));
}

// ---------------------------------------------------------------------------------------------

LikertMeansData likert_means_data(const report::LikertAnalysis& a) {
  if (a.two_sample) {
    throw InvalidData("Likert means: a two-sample analysis has no reference to plot against");
  }
  LikertMeansData d;
  d.scale_min = a.scale_min;
  d.scale_max = a.scale_max;
  d.reference = a.reference;
  d.conf_level = a.settings.test.conf_level;
  d.alpha = a.settings.alpha;
  d.p_adjust = std::string(stats::to_string(a.settings.p_adjust));
  d.names = a.names;
  d.groups = a.groups;
  for (const auto& row : a.rows) {
    if (row.result.test != "one_sample_t") continue;
    LikertMean m;
    m.name = row.metric;
    m.group = row.group1;
    m.mean = value(row.result.mean1);
    m.conf_low = value(row.result.conf_low);
    m.conf_high = value(row.result.conf_high);
    m.differs = differs(row);
    d.means.push_back(std::move(m));
  }
  return d;
}

Figure likert_means_figure(const report::LikertAnalysis& a) {
  return likert_means_figure(likert_means_data(a));
}

Figure likert_means_figure(const LikertMeansData& d) {
  Figure f;
  Panel p;
  // Items from top to bottom in the table's order; conditions side by side within an item.
  const std::size_t items = d.names.size();
  const std::size_t groups = std::max<std::size_t>(1, d.groups.size());
  const MetricRange range{static_cast<double>(d.scale_min), static_cast<double>(d.scale_max)};
  for (std::size_t g = 0; g < d.groups.size(); ++g) {
    Line l;
    l.label = condition_name(d.groups[g]);
    l.style = style_of_condition(d.groups, d.groups[g]);
    l.connect = false;
    l.error_bars = ErrorBars::horizontal;
    const double offset = groups == 1 ? 0.0 : 0.36 * (static_cast<double>(g) / (groups - 1) - 0.5);
    for (const auto& m : d.means) {
      if (m.group != d.groups[g]) continue;
      const auto pos = std::find(d.names.begin(), d.names.end(), m.name) - d.names.begin();
      l.y.push_back(static_cast<double>(items - 1 - static_cast<std::size_t>(pos)) - offset);
      l.x.push_back(m.mean);
      l.lo.push_back(clip(m.conf_low, range));
      l.hi.push_back(clip(m.conf_high, range));
      l.filled.push_back(m.differs);
    }
    f.legend.push_back({LegendEntry::Kind::marker, l.label, l.style, false});
    p.lines.push_back(std::move(l));
  }
  f.legend.push_back(
      {LegendEntry::Kind::marker,
       fmt::format("hollow: ≈ R (p ≥ {}{})", p_threshold(d.alpha), adjust_words(d.p_adjust)),
       Style{Colour{0.3, 0.3, 0.3}, Dash::solid, Marker::circle}, true});
  for (std::size_t i = 0; i < items; ++i) {
    p.y.categories.emplace_back(static_cast<double>(items - 1 - i), d.names[i]);
  }
  p.refs.push_back({d.reference, true, fmt::format("R = {:g}", d.reference)});
  p.x.min = d.scale_min - 0.25;
  p.x.max = d.scale_max + 0.25;
  for (int v = d.scale_min; v <= d.scale_max; ++v) p.x.ticks.push_back(v);
  p.x.label = fmt::format("Mean rating ± {:g}% CI (scale {}–{})", d.conf_level * 100, d.scale_min,
                          d.scale_max);
  f.aspect = std::clamp(0.12 * static_cast<double>(items * groups) + 0.1, 0.3, 0.9);
  f.max_plot_height = 12.0 * static_cast<double>(items * groups) + 20;
  f.panels.push_back(std::move(p));
  return f;
}

std::string alt_text(const LikertMeansData& d) {
  std::size_t differ = 0, finite = 0;
  const LikertMean* lo = nullptr;
  const LikertMean* hi = nullptr;
  for (const auto& m : d.means) {
    if (!std::isfinite(m.mean)) continue;
    ++finite;
    differ += m.differs ? 1 : 0;
    if (lo == nullptr || m.mean < lo->mean) lo = &m;
    if (hi == nullptr || m.mean > hi->mean) hi = &m;
  }
  std::string s = fmt::format(
      "Mean rating of each questionnaire item ({}) on the {}\u2013{} scale for {}, with {:g}% "
      "confidence intervals, against the reference {:g}.",
      and_list(d.names), d.scale_min, d.scale_max, and_list(condition_names(d.groups)),
      d.conf_level * 100, d.reference);
  if (lo != nullptr) {
    s += fmt::format(
        " Means range from {} ({}, {}) to {} ({}, {}); {} of {} differ from the "
        "reference.",
        number(lo->mean), lo->name, condition_name(lo->group), number(hi->mean), hi->name,
        condition_name(hi->group), differ, finite);
  }
  return s;
}

namespace {

// The label of each scale point: the user's label map, else the built-in agree/disagree map.
std::vector<std::string> answer_labels(const report::LikertAnalysis& a) {
  std::vector<io::LabelEntry> map = a.settings.load.labels;
  if (map.empty()) map = io::builtin_agree_labels(a.scale_min, a.scale_max);
  std::vector<std::string> out;
  for (int v = a.scale_min; v <= a.scale_max; ++v) {
    const auto it =
        std::find_if(map.begin(), map.end(), [&](const io::LabelEntry& e) { return e.value == v; });
    out.push_back(it != map.end() ? it->text : std::to_string(v));
  }
  return out;
}

Colour mix(const Colour& a, const Colour& b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// A diverging scale: reddish purple below the neutral point, bluish green above (Okabe-Ito; not
// the conditions' blue and orange), the neutral point grey; darker with the distance from
// neutral, so the order survives greyscale.
std::vector<Colour> diverging_colours(int lo, int hi, double neutral) {
  const Colour light{0.95, 0.95, 0.95};
  const double reach = std::max(neutral - lo, hi - neutral);
  std::vector<Colour> out;
  for (int v = lo; v <= hi; ++v) {
    const double d = (v - neutral) / reach;  // -1 .. 1
    if (d == 0) {
      out.push_back({0.78, 0.78, 0.78});
    } else {
      const double t = 0.35 + 0.65 * std::fabs(d);
      const Colour end = d < 0 ? Colour{0.55, 0.22, 0.45} : Colour{0.0, 0.45, 0.33};
      out.push_back(mix(light, end, t));
    }
  }
  return out;
}

}  // namespace

LikertDistribution likert_distribution_data(const report::LikertAnalysis& a) {
  LikertDistribution d;
  d.scale_min = a.scale_min;
  d.scale_max = a.scale_max;
  d.neutral = a.neutral;
  d.answer_labels = answer_labels(a);
  d.groups = a.groups;
  if (d.groups.empty()) d.groups.push_back("");
  for (const auto& s : a.summaries) {
    if (s.composite || s.counts.empty()) continue;
    LikertBar b;
    b.name = s.name;
    b.group = s.group;
    b.n = s.n;
    double below = 0, at = 0;
    for (std::size_t k = 0; k < s.counts.size(); ++k) {
      const double pct = s.n == 0 ? 0.0 : 100.0 * static_cast<double>(s.counts[k]) / s.n;
      b.percent.push_back(pct);
      const double point = a.scale_min + static_cast<double>(k);
      if (point < a.neutral) below += pct;
      if (point == a.neutral) at += pct;
    }
    b.start = -(below + at / 2);
    d.bars.push_back(std::move(b));
  }
  return d;
}

Figure likert_distribution_figure(const report::LikertAnalysis& a) {
  return likert_distribution_figure(likert_distribution_data(a));
}

Figure likert_distribution_figure(const LikertDistribution& d) {
  Figure f;
  const std::vector<Colour> colours = diverging_colours(d.scale_min, d.scale_max, d.neutral);
  for (int v = d.scale_min; v <= d.scale_max; ++v) {
    const auto k = static_cast<std::size_t>(v - d.scale_min);
    const std::string label = k < d.answer_labels.size() ? d.answer_labels[k] : std::to_string(v);
    f.legend.push_back({LegendEntry::Kind::box,
                        label == std::to_string(v) ? label : fmt::format("{} {}", v, label),
                        Style{colours[k], Dash::solid, Marker::none}, false});
  }
  std::size_t items = 0;
  for (const auto& g : d.groups) {
    Panel p;
    p.title = g;
    Bars b;
    b.horizontal = true;
    b.colours = colours;
    std::vector<const LikertBar*> rows;
    for (const auto& bar : d.bars) {
      if (bar.group == g) rows.push_back(&bar);
    }
    if (rows.empty()) continue;
    items = rows.size();
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double pos = static_cast<double>(rows.size() - 1 - i);
      b.positions.push_back(pos);
      b.segments.push_back(rows[i]->percent);
      b.start.push_back(rows[i]->start);
      p.y.categories.emplace_back(pos, fmt::format("{} (n={})", rows[i]->name, rows[i]->n));
    }
    p.bars = std::move(b);
    p.refs.push_back({0.0, true, ""});
    p.x.min = -100;
    p.x.max = 100;
    p.x.ticks = {-100, -50, 0, 50, 100};
    p.x.percent = true;
    p.x.absolute_labels = true;
    p.x.label = "← disagree    Answers (%)    agree →";
    f.panels.push_back(std::move(p));
  }
  f.columns = 1;
  f.shared_axes = true;
  f.aspect = std::clamp(0.09 * static_cast<double>(items) + 0.08, 0.25, 0.8);
  f.max_plot_height = 16.0 * static_cast<double>(items) + 12;  // bars of the same thickness
  return f;
}

std::string alt_text(const LikertDistribution& d) {
  std::vector<std::string> items;
  std::vector<std::string> parts;
  for (const auto& b : d.bars) {
    if (std::find(items.begin(), items.end(), b.name) == items.end()) items.push_back(b.name);
    double agree = 0;
    for (std::size_t k = 0; k < b.percent.size(); ++k) {
      if (d.scale_min + static_cast<double>(k) > d.neutral) agree += b.percent[k];
    }
    parts.push_back(fmt::format("{} {}: {:.0f}%", b.name, condition_name(b.group), agree));
  }
  return fmt::format(
      "Diverging stacked bars of the answers to each item ({}) for {}, from {} on the left to {} "
      "on the right, centred on the neutral point {:g}. Share above neutral: {}.",
      and_list(items), and_list(condition_names(d.groups)),
      d.answer_labels.empty() ? std::to_string(d.scale_min) : d.answer_labels.front(),
      d.answer_labels.empty() ? std::to_string(d.scale_max) : d.answer_labels.back(), d.neutral,
      fmt::join(parts, ", "));
}

// ---------------------------------------------------------------------------------------------

double Occurrence::share(std::size_t c, std::size_t i, std::size_t s) const {
  std::size_t total = 0;
  for (std::size_t n : counts[c][i]) total += n;
  return total == 0 ? 0.0 : static_cast<double>(counts[c][i][s]) / static_cast<double>(total);
}

Occurrence strategy_occurrence(const std::vector<TrialLabel>& labels) {
  Occurrence o;
  std::set<long long> its;
  std::set<std::string> strategies;
  for (const auto& t : labels) {
    if (std::find(o.conditions.begin(), o.conditions.end(), t.condition) == o.conditions.end()) {
      o.conditions.push_back(t.condition);
    }
    its.insert(t.iteration);
    strategies.insert(t.strategy.empty() ? "(none)" : t.strategy);
  }
  o.iterations.assign(its.begin(), its.end());
  o.strategies.assign(strategies.begin(), strategies.end());
  o.counts.assign(o.conditions.size(),
                  std::vector<std::vector<std::size_t>>(
                      o.iterations.size(), std::vector<std::size_t>(o.strategies.size(), 0)));
  for (const auto& t : labels) {
    const auto c = std::find(o.conditions.begin(), o.conditions.end(), t.condition);
    const auto i = std::lower_bound(o.iterations.begin(), o.iterations.end(), t.iteration);
    const auto s = std::lower_bound(o.strategies.begin(), o.strategies.end(),
                                    t.strategy.empty() ? "(none)" : t.strategy);
    ++o.counts[static_cast<std::size_t>(c - o.conditions.begin())][static_cast<std::size_t>(
        i - o.iterations.begin())][static_cast<std::size_t>(s - o.strategies.begin())];
  }
  return o;
}

Figure occurrence_figure(const Occurrence& o) {
  Figure f;
  std::vector<Colour> colours;
  f.legend.push_back({LegendEntry::Kind::text, "Strategy:", {}, false});
  for (std::size_t s = 0; s < o.strategies.size(); ++s) {
    colours.push_back(strategy_colour(s));
    f.legend.push_back({LegendEntry::Kind::box, o.strategies[s],
                        Style{strategy_colour(s), Dash::solid, Marker::none}, false});
  }
  for (std::size_t c = 0; c < o.conditions.size(); ++c) {
    Panel p;
    p.title = condition_name(o.conditions[c]);
    Bars b;
    b.colours = colours;
    b.thickness = 0.8;
    for (std::size_t i = 0; i < o.iterations.size(); ++i) {
      b.positions.push_back(static_cast<double>(o.iterations[i]));
      std::vector<double> seg;
      for (std::size_t s = 0; s < o.strategies.size(); ++s) seg.push_back(o.share(c, i, s));
      b.segments.push_back(std::move(seg));
    }
    p.bars = std::move(b);
    if (!o.iterations.empty()) {
      p.x.min = static_cast<double>(o.iterations.front()) - 0.6;
      p.x.max = static_cast<double>(o.iterations.back()) + 0.6;
      p.x.ticks = iteration_ticks(o.iterations.front(), o.iterations.back());
    }
    p.x.label = "Iteration";
    p.y.min = 0;
    p.y.max = 1;
    p.y.ticks = {0, 0.25, 0.5, 0.75, 1};
    p.y.label = "Share of participants";
    f.panels.push_back(std::move(p));
  }
  f.columns = 2;
  f.shared_axes = true;
  f.aspect = 0.9;
  return f;
}

std::string alt_text(const Occurrence& o) {
  std::vector<std::string> parts;
  for (std::size_t c = 0; c < o.conditions.size(); ++c) {
    std::vector<std::size_t> total(o.strategies.size(), 0);
    std::size_t all = 0;
    for (std::size_t i = 0; i < o.iterations.size(); ++i) {
      for (std::size_t s = 0; s < o.strategies.size(); ++s) {
        total[s] += o.counts[c][i][s];
        all += o.counts[c][i][s];
      }
    }
    std::vector<std::string> shares;
    for (std::size_t s = 0; s < o.strategies.size(); ++s) {
      shares.push_back(fmt::format(
          "{} {:.0f}%", o.strategies[s],
          all == 0 ? 0.0 : 100.0 * static_cast<double>(total[s]) / static_cast<double>(all)));
    }
    parts.push_back(
        fmt::format("{}: {}", condition_name(o.conditions[c]), fmt::join(shares, ", ")));
  }
  return fmt::format(
      "Stacked bars of the share of participants shown each strategy ({}) per iteration, one "
      "panel per condition ({}). Over all iterations, {}.",
      and_list(o.strategies), and_list(condition_names(o.conditions)), fmt::join(parts, "; "));
}

// ---------------------------------------------------------------------------------------------

Figure traces_figure(const std::vector<TraceCurve>& curves, double conf_level) {
  Figure f;
  // Exposures are not conditions: black and grey, solid and dashed.
  const Style first{Colour{0, 0, 0}, Dash::solid, Marker::none};
  const Style later{Colour{0.5, 0.5, 0.5}, Dash::dashed, Marker::none};
  f.legend.push_back({LegendEntry::Kind::band,
                      fmt::format("first exposure (± {:g}% CI)", conf_level * 100), first, false});
  f.legend.push_back({LegendEntry::Kind::band, "later exposures", later, false});
  std::size_t i = 0;
  while (i < curves.size()) {
    Panel p;
    const std::string& strategy = curves[i].strategy;
    const std::string& variant = curves[i].variant;
    std::size_t n_first = 0, n_later = 0;
    for (; i < curves.size() && curves[i].strategy == strategy && curves[i].variant == variant;
         ++i) {
      const TraceCurve& c = curves[i];
      Line l;
      l.style = c.first_exposure ? first : later;
      l.line_width = 1.2;
      l.band = true;
      for (std::size_t k = 0; k < c.mean.size(); ++k) {
        l.x.push_back(static_cast<double>(k) / static_cast<double>(c.mean.size() - 1));
      }
      l.y = c.mean;
      l.lo = c.conf_low;
      l.hi = c.conf_high;
      (c.first_exposure ? n_first : n_later) = c.trials;
      p.lines.push_back(std::move(l));
    }
    p.title = fmt::format("{}{}", strategy.empty() ? "(none)" : strategy,
                          variant.empty() ? "" : "/" + variant);
    p.note = fmt::format("n = {} / {}", n_first, n_later);
    p.refs.push_back({0.5, false, ""});
    p.x.min = 0;
    p.x.max = 1;
    p.x.ticks = {0, 0.5, 1};
    p.x.label = "Normalised time";
    p.y.min = 0;
    p.y.max = 1;
    p.y.bound_min = 0;
    p.y.bound_max = 1;
    p.y.ticks = {0, 0.5, 1};
    p.y.label = "Pad (true target = 1)";
    f.panels.push_back(std::move(p));
  }
  f.columns = 4;
  f.aspect = 0.8;
  f.shared_axes = true;
  return f;
}

std::string alt_text(const TracesFigureData& d) {
  std::vector<std::string> panels;
  double end[2] = {0, 0};
  std::size_t n[2] = {0, 0};
  for (const auto& c : d.curves) {
    const std::string name = c.strategy + (c.variant.empty() ? "" : "/" + c.variant);
    if (std::find(panels.begin(), panels.end(), name) == panels.end()) panels.push_back(name);
    if (c.mean.empty() || !std::isfinite(c.mean.back())) continue;
    end[c.first_exposure ? 0 : 1] += c.mean.back();
    ++n[c.first_exposure ? 0 : 1];
  }
  std::string s = fmt::format(
      "Mean pad position over normalised time, one panel per strategy and version ({}), mirrored "
      "so that the true target is at 1; first exposure (solid) against later exposures (dashed), "
      "with {:g}% confidence bands.",
      and_list(panels), d.conf_level * 100);
  if (n[0] > 0 && n[1] > 0) {
    s += fmt::format(
        " At the end of the trial the first exposures average {} and the later ones "
        "{}.",
        number(end[0] / static_cast<double>(n[0])), number(end[1] / static_cast<double>(n[1])));
  }
  return s;
}

}  // namespace feint::plot
