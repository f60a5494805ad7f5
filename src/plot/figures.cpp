// The study's figures: data from the tables' tidy rows, then the drawing description.
#include "feint/plot/figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
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

// Iteration ticks: 1 and round numbers up to the last iteration.
std::vector<double> iteration_ticks(long long first, long long last) {
  std::vector<double> t = detail::nice_ticks(static_cast<double>(first), static_cast<double>(last));
  if (t.size() >= 2 && first >= 0 && t.front() - static_cast<double>(first) >= (t[1] - t[0]) / 2) {
    t.insert(t.begin(), static_cast<double>(first));
  }
  return t;
}

std::string condition_name(const std::string& c) { return c.empty() ? "all participants" : c; }

}  // namespace

std::string metric_axis_label(const std::string& metric) {
  if (metric == "error") return "Error (pad units)";
  if (metric == "confusion") return "Confusion (fraction, 0\u20131)";
  std::string s = metric;
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

// ---------------------------------------------------------------------------------------------

MetricFigureData metric_figure_data(const report::Table1& one_sample,
                                    const report::Table1* comparison, const std::string& metric) {
  MetricFigureData d;
  d.metric = metric;
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

Figure metric_figure(const MetricFigureData& d) {
  Figure f;
  Panel p;
  long long first = std::numeric_limits<long long>::max(), last = 0;
  for (std::size_t s = 0; s < d.series.size(); ++s) {
    Line l;
    l.label = condition_name(d.series[s].condition);
    l.style = series_style(s);
    l.band = true;
    for (const auto& pt : d.series[s].points) {
      l.x.push_back(static_cast<double>(pt.iteration));
      l.y.push_back(pt.mean);
      l.lo.push_back(pt.conf_low);
      l.hi.push_back(pt.conf_high);
      l.filled.push_back(pt.differs);
      first = std::min(first, pt.iteration);
      last = std::max(last, pt.iteration);
    }
    f.legend.push_back({LegendEntry::Kind::band, l.label, l.style, false});
    p.lines.push_back(std::move(l));
  }
  const std::string adjust = d.p_adjust == "none" ? "" : fmt::format(", {}", d.p_adjust);
  f.legend.push_back({LegendEntry::Kind::marker,
                      fmt::format("hollow: \u2248 R (p \u2265 {}{})", p_threshold(d.alpha), adjust),
                      Style{okabe_ito(0), Dash::solid, Marker::circle}, true});
  if (!d.group1.empty()) {
    f.legend.push_back(
        {LegendEntry::Kind::asterisk,
         fmt::format("{} \u2260 {} (p < {}{})", d.group1, d.group2, p_threshold(d.alpha), adjust),
         {},
         false});
    for (long long it : d.marked) p.marks.push_back(static_cast<double>(it));
  }
  p.refs.push_back({d.reference, false, fmt::format("R = {:g}", d.reference)});
  p.x.label = "Iteration";
  if (first <= last) {
    p.x.min = static_cast<double>(first) - 0.5;
    p.x.max = static_cast<double>(last) + 0.5;
    p.x.ticks = iteration_ticks(first, last);
  }
  p.y.label = fmt::format("{} \u00b1 {:g}% CI", metric_axis_label(d.metric), d.conf_level * 100);
  f.panels.push_back(std::move(p));
  return f;
}

// ---------------------------------------------------------------------------------------------

std::vector<LikertMean> likert_means_data(const report::LikertAnalysis& a) {
  if (a.two_sample) {
    throw InvalidData("Likert means: a two-sample analysis has no reference to plot against");
  }
  std::vector<LikertMean> out;
  for (const auto& row : a.rows) {
    if (row.result.test != "one_sample_t") continue;
    LikertMean m;
    m.name = row.metric;
    m.group = row.group1;
    m.mean = value(row.result.mean1);
    m.conf_low = value(row.result.conf_low);
    m.conf_high = value(row.result.conf_high);
    m.differs = differs(row);
    out.push_back(std::move(m));
  }
  return out;
}

Figure likert_means_figure(const report::LikertAnalysis& a) {
  const std::vector<LikertMean> means = likert_means_data(a);
  Figure f;
  Panel p;
  // Items from top to bottom in the table's order; conditions side by side within an item.
  const std::size_t items = a.names.size();
  const std::size_t groups = std::max<std::size_t>(1, a.groups.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) {
    Line l;
    l.label = condition_name(a.groups[g]);
    l.style = series_style(g);
    l.connect = false;
    l.error_bars = ErrorBars::horizontal;
    const double offset = groups == 1 ? 0.0 : 0.36 * (static_cast<double>(g) / (groups - 1) - 0.5);
    for (const auto& m : means) {
      if (m.group != a.groups[g]) continue;
      const auto pos = std::find(a.names.begin(), a.names.end(), m.name) - a.names.begin();
      l.y.push_back(static_cast<double>(items - 1 - static_cast<std::size_t>(pos)) - offset);
      l.x.push_back(m.mean);
      l.lo.push_back(m.conf_low);
      l.hi.push_back(m.conf_high);
      l.filled.push_back(m.differs);
    }
    f.legend.push_back({LegendEntry::Kind::marker, l.label, l.style, false});
    p.lines.push_back(std::move(l));
  }
  f.legend.push_back({LegendEntry::Kind::marker,
                      fmt::format("hollow: \u2248 R (p \u2265 {}{})", p_threshold(a.settings.alpha),
                                  a.settings.p_adjust == stats::PAdjustMethod::none
                                      ? ""
                                      : fmt::format(", {}", stats::to_string(a.settings.p_adjust))),
                      Style{okabe_ito(0), Dash::solid, Marker::circle}, true});
  for (std::size_t i = 0; i < items; ++i) {
    p.y.categories.emplace_back(static_cast<double>(items - 1 - i), a.names[i]);
  }
  p.refs.push_back({a.reference, true, fmt::format("R = {:g}", a.reference)});
  p.x.min = a.scale_min - 0.25;
  p.x.max = a.scale_max + 0.25;
  for (int v = a.scale_min; v <= a.scale_max; ++v) p.x.ticks.push_back(v);
  p.x.label = fmt::format("Mean rating \u00b1 {:g}% CI (scale {}\u2013{})",
                          a.settings.test.conf_level * 100, a.scale_min, a.scale_max);
  f.aspect = std::clamp(0.12 * static_cast<double>(items * groups) + 0.1, 0.3, 0.9);
  f.max_plot_height = 12.0 * static_cast<double>(items * groups) + 20;
  f.panels.push_back(std::move(p));
  return f;
}

std::vector<LikertBar> likert_distribution_data(const report::LikertAnalysis& a) {
  std::vector<LikertBar> out;
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
    out.push_back(std::move(b));
  }
  return out;
}

namespace {

Colour mix(const Colour& a, const Colour& b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// A diverging scale: vermillion below the neutral point, blue above (Okabe-Ito), the neutral
// point grey; darker with the distance from neutral, so the order survives greyscale.
std::vector<Colour> diverging_colours(int lo, int hi, double neutral) {
  const Colour light{0.93, 0.93, 0.93};
  const double reach = std::max(neutral - lo, hi - neutral);
  std::vector<Colour> out;
  for (int v = lo; v <= hi; ++v) {
    const double d = (v - neutral) / reach;  // -1 .. 1
    if (d == 0) {
      out.push_back({0.75, 0.75, 0.75});
    } else {
      const double t = 0.3 + 0.7 * std::fabs(d);
      out.push_back(mix(light, d < 0 ? okabe_ito(6) : okabe_ito(5), t));
    }
  }
  return out;
}

}  // namespace

Figure likert_distribution_figure(const report::LikertAnalysis& a) {
  const std::vector<LikertBar> bars = likert_distribution_data(a);
  Figure f;
  const std::vector<Colour> colours = diverging_colours(a.scale_min, a.scale_max, a.neutral);
  for (int v = a.scale_min; v <= a.scale_max; ++v) {
    std::string label = std::to_string(v);
    if (v == a.scale_min) label += " (lowest)";
    if (v == a.scale_max) label += " (highest)";
    f.legend.push_back(
        {LegendEntry::Kind::box, label,
         Style{colours[static_cast<std::size_t>(v - a.scale_min)], Dash::solid, Marker::none},
         false});
  }
  std::vector<std::string> groups = a.groups;
  if (groups.empty()) groups.push_back("");
  std::size_t items = 0;
  for (const auto& g : groups) {
    Panel p;
    p.title = g;
    Bars b;
    b.horizontal = true;
    b.colours = colours;
    std::vector<const LikertBar*> rows;
    for (const auto& bar : bars) {
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
    p.x.label = fmt::format("Answers (%), centred on neutral ({:g})", a.neutral);
    f.panels.push_back(std::move(p));
  }
  f.columns = 1;
  f.shared_axes = true;
  f.aspect = std::clamp(0.09 * static_cast<double>(items) + 0.08, 0.25, 0.8);
  f.max_plot_height = 16.0 * static_cast<double>(items) + 12;  // bars of the same thickness
  return f;
}

// ---------------------------------------------------------------------------------------------

Figure occurrence_figure(const Occurrence& o) {
  Figure f;
  std::vector<Colour> colours;
  for (std::size_t s = 0; s < o.strategies.size(); ++s) {
    colours.push_back(series_style(s).colour);
    f.legend.push_back({LegendEntry::Kind::box, o.strategies[s], series_style(s), false});
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

// ---------------------------------------------------------------------------------------------

Figure participants_figure(const io::ScoresTable& scores, const std::string& metric,
                           const report::Table1* one_sample) {
  const int m = scores.metric_index(metric);
  if (m < 0) throw InvalidData(fmt::format("figure participants: metric '{}' not loaded", metric));
  Figure f;
  const auto conditions = scores.conditions();
  const auto iterations = scores.iterations();
  std::optional<MetricFigureData> means;
  if (one_sample != nullptr) means = metric_figure_data(*one_sample, nullptr, metric);
  for (std::size_t c = 0; c < conditions.size(); ++c) {
    Panel p;
    p.title = condition_name(conditions[c]);
    // Participants in order of first appearance; their rows sorted by iteration.
    std::map<std::string, std::vector<std::pair<long long, double>>> rows;
    std::vector<std::string> order;
    for (const auto& r : scores.records) {
      if (r.condition != conditions[c]) continue;
      auto [pos, fresh] = rows.try_emplace(r.participant);
      if (fresh) order.push_back(r.participant);
      pos->second.emplace_back(r.iteration, value(r.values[static_cast<std::size_t>(m)]));
    }
    for (const auto& who : order) {
      auto pts = rows[who];
      std::sort(pts.begin(), pts.end());
      Line l;
      l.style = Style{okabe_ito(0), Dash::solid, Marker::none};
      l.opacity = 0.3;
      l.line_width = 0.5;
      long long prev = std::numeric_limits<long long>::min();
      for (const auto& [it, v] : pts) {
        if (prev != std::numeric_limits<long long>::min() && it != prev + 1) {
          l.x.push_back(static_cast<double>(prev) + 0.5);  // a skipped iteration breaks the line
          l.y.push_back(std::numeric_limits<double>::quiet_NaN());
        }
        l.x.push_back(static_cast<double>(it));
        l.y.push_back(v);
        prev = it;
      }
      p.lines.push_back(std::move(l));
    }
    if (means) {
      for (const auto& s : means->series) {
        if (s.condition != conditions[c]) continue;
        Line l;
        l.style = series_style(c);
        l.style.marker = Marker::none;
        l.line_width = 1.6;
        for (const auto& pt : s.points) {
          l.x.push_back(static_cast<double>(pt.iteration));
          l.y.push_back(pt.mean);
        }
        p.lines.push_back(std::move(l));
      }
      p.refs.push_back({means->reference, false, fmt::format("R = {:g}", means->reference)});
    }
    if (!iterations.empty()) {
      p.x.min = static_cast<double>(iterations.front()) - 0.5;
      p.x.max = static_cast<double>(iterations.back()) + 0.5;
      p.x.ticks = iteration_ticks(iterations.front(), iterations.back());
    }
    p.x.label = "Iteration";
    p.y.label = metric_axis_label(metric);
    f.panels.push_back(std::move(p));
  }
  f.shared_axes = true;
  f.max_columns_narrow = 1;  // one panel per row in a column: the lines need the width
  f.legend.push_back({LegendEntry::Kind::line, "one participant",
                      Style{Colour{0.6, 0.6, 0.6}, Dash::solid, Marker::none}, false});
  if (means) {
    for (std::size_t c = 0; c < conditions.size(); ++c) {
      Style s = series_style(c);
      s.marker = Marker::none;
      f.legend.push_back({LegendEntry::Kind::line,
                          fmt::format("mean, {}", condition_name(conditions[c])), s, false});
    }
  }
  f.columns = 2;
  return f;
}

// ---------------------------------------------------------------------------------------------

Figure traces_figure(const std::vector<TraceCurve>& curves, double conf_level) {
  Figure f;
  const Style first = series_style(0), later = series_style(1);
  f.legend.push_back({LegendEntry::Kind::band,
                      fmt::format("first exposure (\u00b1 {:g}% CI)", conf_level * 100), first,
                      false});
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
      l.style.marker = Marker::none;
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
    p.y.ticks = {0, 0.5, 1};
    p.y.label = "Pad (true target = 1)";
    f.panels.push_back(std::move(p));
  }
  f.columns = 4;
  f.aspect = 0.8;
  f.shared_axes = true;
  return f;
}

}  // namespace feint::plot
