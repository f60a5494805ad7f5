// The study's figures of a metric: per iteration, per participant, against exposure, and the
// mixed model's fit (data from upstream results, the drawing description, the alt text).
#include "feint/plot/figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "feint/error.hpp"
#include "feint/tables/writers.hpp"
#include "figure_detail.hpp"

namespace feint::plot {

using namespace figure_detail;

namespace {

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
  if (metric == "error") return {0.0, 1.0};
  // Confusion is >= 0 on both scales, and unbounded above on the raw one, the default
  // (docs/metrics.md "One scale"): a [0, 1] axis would clip a raw score of 1.8.
  if (metric == "confusion") return {0.0, std::numeric_limits<double>::infinity()};
  return {};
}

std::string metric_axis_label(const std::string& metric) {
  if (metric == "error") return "Error (pad units)";
  if (metric == "confusion") return "Confusion";  // its scale (raw or speed) is the scores'

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

MetricFigureData metric_figure_data(const tables::Table1& one_sample,
                                    const tables::Table1* comparison, const std::string& metric) {
  return metric_figure_data(one_sample, comparison, metric, metric_range(metric));
}

MetricFigureData metric_figure_data(const tables::Table1& one_sample,
                                    const tables::Table1* comparison, const std::string& metric,
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
      const tables::TidyRow& row = one_sample.rows[block.cells[i][m].difference_row];
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
                      fmt::format("hollow: n.s. against R (p \u2265 {}{})", p_threshold(d.alpha), adjust),
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
                                   const tables::Table1* one_sample) {
  return participants_data(scores, metric, one_sample, metric_range(metric));
}

ParticipantsData participants_data(const io::ScoresTable& scores, const std::string& metric,
                                   const tables::Table1* one_sample, MetricRange range) {
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
                           const tables::Table1* one_sample) {
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

}  // namespace feint::plot
