// The questionnaire's figures: diverging stacked bars with the answer labels, and the item means.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"
#include "feint/plot/figures.hpp"
#include "feint/tables/writers.hpp"
#include "figure_detail.hpp"

namespace feint::plot {

using namespace figure_detail;

LikertMeansData likert_means_data(const tables::LikertAnalysis& a) {
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

Figure likert_means_figure(const tables::LikertAnalysis& a) {
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
       fmt::format("hollow: n.s. against R (p ≥ {}{})", p_threshold(d.alpha), adjust_words(d.p_adjust)),
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
std::vector<std::string> answer_labels(const tables::LikertAnalysis& a) {
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

LikertDistribution likert_distribution_data(const tables::LikertAnalysis& a) {
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

Figure likert_distribution_figure(const tables::LikertAnalysis& a) {
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

}  // namespace feint::plot
