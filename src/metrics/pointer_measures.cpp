#include "feint/metrics/pointer_measures.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <limits>

#include "feint/error.hpp"

// Each computation follows mousetrap's R code step by step, down to R's accumulation: sum(),
// mean(), cumsum() and rowSums() add in long double, so the values agree to the last bits and ties
// (which.max: the first maximum) fall where mousetrap's fall.

namespace feint::metrics {

namespace {

// R's sum() of doubles.
double r_sum(std::span<const double> v) {
  long double s = 0;
  for (double d : v) s += d;
  return static_cast<double>(s);
}

// R's mean() of doubles: the long double mean, then one correction pass.
double r_mean(std::span<const double> v) {
  const auto n = static_cast<long double>(v.size());
  long double s = 0;
  for (double d : v) s += d;
  s /= n;
  if (std::isfinite(static_cast<double>(s))) {
    long double c = 0;
    for (double d : v) c += d - s;
    s += c / n;
  }
  return static_cast<double>(s);
}

// rowSums() of two squares.
double r_sum2(double a, double b) {
  return static_cast<double>(static_cast<long double>(a) + static_cast<long double>(b));
}

// which.max / which.min: the first extreme, NaN skipped (0-based here).
template <class Better>
std::size_t first_extreme(std::span<const double> v, Better better) {
  std::size_t at = v.size();
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::isnan(v[i])) continue;
    if (at == v.size() || better(v[i], v[at])) at = i;
  }
  return at;
}
std::size_t which_max(std::span<const double> v) {
  return first_extreme(v, [](double a, double b) { return a > b; });
}
std::size_t which_min(std::span<const double> v) {
  return first_extreme(v, [](double a, double b) { return a < b; });
}

// sum(abs(diff(side))) for a logical vector.
int side_changes(const std::vector<bool>& side) {
  int n = 0;
  for (std::size_t i = 1; i < side.size(); ++i) n += side[i] != side[i - 1] ? 1 : 0;
  return n;
}

}  // namespace

namespace detail {

void check_pointer_trace(std::span<const PointerSample> trace) {
  const std::size_t n = trace.size();
  if (n < 2) {
    throw InvalidData(
        fmt::format("pointer trace: {} sample{}; at least 2 are needed", n, n == 1 ? "" : "s"));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const PointerSample& s = trace[i];
    if (!std::isfinite(s.t) || !std::isfinite(s.x) || !std::isfinite(s.y)) {
      throw InvalidData(
          fmt::format("pointer trace: sample {} of {} (t = {}, x = {}, y = {}) is not "
                      "finite",
                      i + 1, n, s.t, s.x, s.y));
    }
    if (i > 0 && !(s.t > trace[i - 1].t)) {
      throw InvalidData(
          fmt::format("pointer trace: sample {} of {}: t = {} does not come after "
                      "t = {} (timestamps must increase strictly)",
                      i + 1, n, s.t, trace[i - 1].t));
    }
  }
}

int count_flips(std::span<const double> pos, double threshold) {
  // Runs of same-signed non-zero steps, each summed (R: cum_delta <- delta + cum_delta).
  std::vector<double> runs;
  for (std::size_t i = 1; i < pos.size(); ++i) {
    const double delta = pos[i] - pos[i - 1];
    if (!(std::fabs(delta) > 0)) continue;
    if (!runs.empty() && std::signbit(runs.back()) == std::signbit(delta)) {
      runs.back() = delta + runs.back();
    } else {
      runs.push_back(delta);
    }
  }
  if (runs.empty()) return 0;
  if (threshold == 0) return static_cast<int>(runs.size()) - 1;
  std::vector<bool> positive;
  for (double r : runs) {
    if (std::fabs(r) > std::fabs(threshold)) positive.push_back(r > 0);
  }
  return side_changes(positive);
}

}  // namespace detail

using detail::check_pointer_trace;

void PointerMeasureSettings::validate() const {
  auto ok = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!ok(flip_threshold)) {
    throw UsageError(
        fmt::format("flip threshold: {} must be a finite distance >= 0", flip_threshold));
  }
  if (hover_threshold && !ok(*hover_threshold)) {
    throw UsageError(
        fmt::format("hover threshold: {} must be a finite time >= 0", *hover_threshold));
  }
  if (!ok(initiation_threshold)) {
    throw UsageError(fmt::format("initiation threshold: {} must be a finite distance >= 0",
                                 initiation_threshold));
  }
}

std::vector<PointerSample> remap_symmetric(std::span<const PointerSample> trace, RemapX remap_x,
                                           RemapY remap_y) {
  check_pointer_trace(trace);
  const PointerSample& end = trace.back();
  const bool flip_x =
      (remap_x == RemapX::left && end.x > 0) || (remap_x == RemapX::right && end.x < 0);
  const bool flip_y =
      (remap_y == RemapY::up && end.y < 0) || (remap_y == RemapY::down && end.y > 0);
  std::vector<PointerSample> out(trace.begin(), trace.end());
  for (PointerSample& s : out) {
    if (flip_x) s.x = -s.x;
    if (flip_y) s.y = -s.y;
  }
  return out;
}

std::vector<PointerSample> align_start(std::span<const PointerSample> trace, double start_x,
                                       double start_y) {
  check_pointer_trace(trace);
  if (!std::isfinite(start_x) || !std::isfinite(start_y)) {
    throw UsageError(fmt::format("align start: ({}, {}) is not a finite point", start_x, start_y));
  }
  const PointerSample first = trace.front();
  std::vector<PointerSample> out(trace.begin(), trace.end());
  for (PointerSample& s : out) {
    s.x = s.x - first.x + start_x;
    s.y = s.y - first.y + start_y;
  }
  return out;
}

namespace {

// seq.int(from, to, length.out = n) as R 4.2 computes it: from + i by, the last one exactly `to`.
std::vector<double> r_seq_length_out(double from, double to, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  const double by = (to - from) / static_cast<double>(n - 1);
  for (int i = 0; i < n - 1; ++i)
    v[static_cast<std::size_t>(i)] = from + static_cast<double>(i) * by;
  v.back() = to;
  return v;
}

// R's approx1 (linear): bisection for t[i] <= v <= t[j], then the value at t[j] or t[i] when v is
// one of them, else y[i] + (y[j] - y[i]) ((v - t[i]) / (t[j] - t[i])).
template <class Y>
double r_approx(double v, std::span<const PointerSample> s, Y y) {
  std::size_t i = 0, j = s.size() - 1;
  while (i + 1 < j) {
    const std::size_t ij = (i + j) / 2;
    if (v < s[ij].t)
      j = ij;
    else
      i = ij;
  }
  if (v == s[j].t) return y(s[j]);
  if (v == s[i].t) return y(s[i]);
  return y(s[i]) + (y(s[j]) - y(s[i])) * ((v - s[i].t) / (s[j].t - s[i].t));
}

}  // namespace

std::vector<PointerSample> time_normalize(std::span<const PointerSample> trace, int nsteps) {
  if (nsteps < 2) {
    throw UsageError(
        fmt::format("time normalisation: {} steps; at least 2 are needed (the first "
                    "and the last timestamp)",
                    nsteps));
  }
  check_pointer_trace(trace);
  const std::vector<double> times = r_seq_length_out(trace.front().t, trace.back().t, nsteps);
  std::vector<PointerSample> out;
  out.reserve(times.size());
  for (double v : times) {
    out.push_back({r_approx(v, trace, [](const PointerSample& s) { return s.t; }),
                   r_approx(v, trace, [](const PointerSample& s) { return s.x; }),
                   r_approx(v, trace, [](const PointerSample& s) { return s.y; })});
  }
  return out;
}

PointerDeviations pointer_deviations(std::span<const PointerSample> trace) {
  check_pointer_trace(trace);
  const std::size_t n = trace.size();
  const PointerSample p1 = trace.front(), p2 = trace.back();
  const bool same = p1.x == p2.x && p1.y == p2.y;
  PointerDeviations d;
  d.x_ideal.resize(n);
  d.y_ideal.resize(n);
  d.dev_ideal.resize(n);
  const double dx = p2.x - p1.x, dy = p2.y - p1.y;
  const double len2 = dx * dx + dy * dy;
  for (std::size_t i = 0; i < n; ++i) {
    const PointerSample& p = trace[i];
    if (same) {  // mousetrap's fallback: no line to project on, the start stands for it
      d.x_ideal[i] = p1.x;
      d.y_ideal[i] = p1.y;
    } else {  // point_to_line (Bourke): the orthogonal projection on the line through p1 and p2
      const double u = ((p.x - p1.x) * dx + (p.y - p1.y) * dy) / len2;
      d.x_ideal[i] = p1.x + u * dx;
      d.y_ideal[i] = p1.y + u * dy;
    }
    const double ex = d.x_ideal[i] - p.x, ey = d.y_ideal[i] - p.y;
    double dev = std::sqrt(r_sum2(ex * ex, ey * ey));
    if (d.y_ideal[i] > p.y) dev = -dev;  // below the path: negative
    d.dev_ideal[i] = dev;
  }
  if (p1.y > p2.y) {  // a path that ends below its start: above and below trade places
    for (double& v : d.dev_ideal) v = -v;
  }
  return d;
}

PointerDerivatives pointer_derivatives(std::span<const PointerSample> trace) {
  check_pointer_trace(trace);
  const std::size_t n = trace.size();
  PointerDerivatives d;
  d.dist.assign(n, 0.0);
  d.vel.assign(n, 0.0);
  d.acc.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double ex = trace[i].x - trace[i - 1].x, ey = trace[i].y - trace[i - 1].y;
    d.dist[i] = std::sqrt(r_sum2(ex * ex, ey * ey));
    d.vel[i] = d.dist[i] / (trace[i].t - trace[i - 1].t);
  }
  // acc[i] = (|vel[i+1]| - |vel[i]|) / dt of the segment ending at sample i (mousetrap divides by
  // the earlier of the two segments' durations); the last sample has no following velocity.
  for (std::size_t i = 1; i + 1 < n; ++i) {
    d.acc[i] = (std::fabs(d.vel[i + 1]) - std::fabs(d.vel[i])) / (trace[i].t - trace[i - 1].t);
  }
  d.acc[n - 1] = std::numeric_limits<double>::quiet_NaN();
  return d;
}

namespace {

void position_measures(std::span<const PointerSample> trace, const PointerMeasureSettings& settings,
                       PointerMeasures& m) {
  std::vector<double> xs, ys;
  for (const PointerSample& s : trace) {
    xs.push_back(s.x);
    ys.push_back(s.y);
  }
  m.xpos_max = xs[which_max(xs)];
  m.xpos_min = xs[which_min(xs)];
  m.ypos_max = ys[which_max(ys)];
  m.ypos_min = ys[which_min(ys)];
  m.xpos_flips = detail::count_flips(xs, settings.flip_threshold);
  m.ypos_flips = detail::count_flips(ys, settings.flip_threshold);
  // Crossings of the axes, samples exactly on an axis left out.
  std::vector<bool> right_of_y_axis, above_x_axis;
  for (const PointerSample& s : trace) {
    if (s.x != 0) right_of_y_axis.push_back(s.x > 0);
    if (s.y != 0) above_x_axis.push_back(s.y > 0);
  }
  m.xpos_reversals = side_changes(right_of_y_axis);
  m.ypos_reversals = side_changes(above_x_axis);
}

// pracma::polyarea of the trace closed by the direct path, its sign set by the end's quadrant.
double area_under_curve(std::span<const PointerSample> trace) {
  const std::size_t n = trace.size();
  long double p1 = 0, p2 = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    p1 += trace[i].x * trace[i + 1].y;
    p2 += trace[i + 1].x * trace[i].y;
  }
  const double a = 0.5 * ((static_cast<double>(p1) + trace[n - 1].x * trace[0].y) -
                          (static_cast<double>(p2) + trace[0].x * trace[n - 1].y));
  const PointerSample& s = trace.front();
  const PointerSample& e = trace.back();
  // Flipped when the trace ends up-right or down-left of its start, so that area above the path
  // counts positive for a trace that ends up-left (as after remap_symmetric).
  if ((e.y > s.y && e.x > s.x) || (e.y < s.y && e.x < s.x)) return -a;
  return a;
}

void deviation_measures(std::span<const PointerSample> trace, PointerMeasures& m) {
  const PointerDeviations d = pointer_deviations(trace);
  std::vector<double> abs_dev;
  for (double v : d.dev_ideal) abs_dev.push_back(std::fabs(v));
  const std::size_t at_mad = which_max(abs_dev);
  const std::size_t at_above = which_max(d.dev_ideal);
  const std::size_t at_below = which_min(d.dev_ideal);
  m.mad = d.dev_ideal[at_mad];
  m.mad_time = trace[at_mad].t;
  m.md_above = d.dev_ideal[at_above];
  m.md_above_time = trace[at_above].t;
  m.md_below = d.dev_ideal[at_below];
  m.md_below_time = trace[at_below].t;
  m.ad = r_mean(d.dev_ideal);
  m.auc = area_under_curve(trace);
}

// The durations of the maximal runs of still segments (mousetrap: cumsum of the still segments'
// durations, read at the end of each run, then differenced).
std::vector<double> still_periods(const std::vector<double>& dt, const std::vector<bool>& still) {
  std::vector<double> at_ends;
  long double cum = 0;
  for (std::size_t i = 0; i < dt.size(); ++i) {
    cum += still[i] ? dt[i] : 0.0;
    const bool run_ends = still[i] && (i + 1 == dt.size() || !still[i + 1]);
    if (run_ends) at_ends.push_back(static_cast<double>(cum));
  }
  for (std::size_t k = at_ends.size(); k-- > 1;) at_ends[k] = at_ends[k] - at_ends[k - 1];
  return at_ends;
}

// idle_time and the hovers, in mousetrap's three cases: the pointer moves at every sample (idle
// = the first timestamp), never moves (idle = RT), or sometimes (the still segments' durations).
void time_measures(std::span<const PointerSample> trace, const PointerMeasureSettings& settings,
                   PointerMeasures& m) {
  const std::size_t n = trace.size();
  m.rt = trace[n - 1].t;
  m.initiation_time = m.rt;
  for (std::size_t i = 0; i < n; ++i) {
    const double ex = trace[i].x - trace[0].x, ey = trace[i].y - trace[0].y;
    if (std::sqrt(ex * ex + ey * ey) > settings.initiation_threshold) {
      m.initiation_time = trace[i - 1].t;  // i >= 1: the first sample is at distance 0
      break;
    }
  }
  std::vector<double> dt;
  std::vector<bool> still;
  std::size_t n_still = 0;
  for (std::size_t i = 1; i < n; ++i) {
    dt.push_back(trace[i].t - trace[i - 1].t);
    still.push_back(trace[i].x - trace[i - 1].x == 0 && trace[i].y - trace[i - 1].y == 0);
    n_still += still.back() ? 1 : 0;
  }
  const std::optional<double> h = settings.hover_threshold;
  if (n_still == 0) {
    m.idle_time = trace[0].t;
    if (h) {
      m.hover_time = trace[0].t > *h ? trace[0].t : 0.0;
      m.hovers = 0;
    }
  } else if (n_still == dt.size()) {
    m.idle_time = m.rt;
    if (h) {
      m.hover_time = m.rt > *h ? m.rt : 0.0;
      m.hovers = m.rt > *h ? 1 : 0;
    }
  } else {
    std::vector<double> still_dt;
    for (std::size_t i = 0; i < dt.size(); ++i) {
      if (still[i]) still_dt.push_back(dt[i]);
    }
    m.idle_time = r_sum(still_dt);
    if (h) {
      std::vector<double> long_ones;
      for (double p : still_periods(dt, still)) {
        if (p > *h) long_ones.push_back(p);
      }
      m.hover_time = r_sum(long_ones);
      m.hovers = static_cast<int>(long_ones.size());
    }
  }
  if (h && !settings.hover_incl_initial && m.initiation_time > *h) {
    // mousetrap subtracts the initial phase whether or not it was counted as a hover above.
    *m.hover_time -= m.initiation_time;
    *m.hovers -= 1;
  }
}

void derivative_measures(std::span<const PointerSample> trace, PointerMeasures& m) {
  const PointerDerivatives d = pointer_derivatives(trace);
  m.total_dist = r_sum(d.dist);
  // vel[i] belongs to the segment (i-1, i); mousetrap means to average its two timestamps but its
  // ifelse() keeps only the first: the segment's start, t[i-1] (t[0] for i = 0).
  const std::size_t at_vmax = which_max(d.vel), at_vmin = which_min(d.vel);
  m.vel_max = d.vel[at_vmax];
  m.vel_max_time = trace[at_vmax == 0 ? 0 : at_vmax - 1].t;
  m.vel_min = d.vel[at_vmin];
  m.vel_min_time = trace[at_vmin == 0 ? 0 : at_vmin - 1].t;
  const std::size_t at_amax = which_max(d.acc), at_amin = which_min(d.acc);
  m.acc_max = d.acc[at_amax];
  m.acc_max_time = trace[at_amax].t;
  m.acc_min = d.acc[at_amin];
  m.acc_min_time = trace[at_amin].t;
}

}  // namespace

PointerMeasures pointer_measures(std::span<const PointerSample> trace,
                                 const PointerMeasureSettings& settings) {
  settings.validate();
  check_pointer_trace(trace);
  if (trace.front().t < 0) {
    throw InvalidData(
        fmt::format("pointer trace: the first timestamp is {} < 0; mousetrap's time "
                    "measures count from tracking start (reset it to 0)",
                    trace.front().t));
  }
  PointerMeasures m;
  position_measures(trace, settings, m);
  deviation_measures(trace, m);
  time_measures(trace, settings, m);
  derivative_measures(trace, m);
  return m;
}

std::vector<std::pair<std::string_view, double>> mousetrap_columns(const PointerMeasures& m) {
  std::vector<std::pair<std::string_view, double>> c = {{"xpos_max", m.xpos_max},
                                                        {"xpos_min", m.xpos_min},
                                                        {"ypos_max", m.ypos_max},
                                                        {"ypos_min", m.ypos_min},
                                                        {"MAD", m.mad},
                                                        {"MAD_time", m.mad_time},
                                                        {"MD_above", m.md_above},
                                                        {"MD_above_time", m.md_above_time},
                                                        {"MD_below", m.md_below},
                                                        {"MD_below_time", m.md_below_time},
                                                        {"AD", m.ad},
                                                        {"AUC", m.auc},
                                                        {"xpos_flips", m.xpos_flips},
                                                        {"ypos_flips", m.ypos_flips},
                                                        {"xpos_reversals", m.xpos_reversals},
                                                        {"ypos_reversals", m.ypos_reversals},
                                                        {"RT", m.rt},
                                                        {"initiation_time", m.initiation_time},
                                                        {"idle_time", m.idle_time}};
  if (m.hover_time) c.emplace_back("hover_time", *m.hover_time);
  if (m.hovers) c.emplace_back("hovers", *m.hovers);
  const std::pair<std::string_view, double> rest[] = {
      {"total_dist", m.total_dist},     {"vel_max", m.vel_max},
      {"vel_max_time", m.vel_max_time}, {"vel_min", m.vel_min},
      {"vel_min_time", m.vel_min_time}, {"acc_max", m.acc_max},
      {"acc_max_time", m.acc_max_time}, {"acc_min", m.acc_min},
      {"acc_min_time", m.acc_min_time}};
  c.insert(c.end(), std::begin(rest), std::end(rest));
  return c;
}

}  // namespace feint::metrics
