// The strategies' figures: strategy occurrence per iteration, and the mean pad traces.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "feint/error.hpp"
#include "feint/plot/figures.hpp"
#include "figure_detail.hpp"

namespace feint::plot {

using namespace figure_detail;

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
