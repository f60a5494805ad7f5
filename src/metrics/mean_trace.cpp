// Mean pad traces per strategy, version and exposure (see mean_trace.hpp).
#include "feint/metrics/mean_trace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"

namespace feint::metrics {

std::vector<TrialLabel> read_trial_labels(const std::string& path) {
  io::CsvReader csv(path);
  const int participant = csv.column("participant");
  const int condition = csv.column("condition");
  const int iteration = csv.column("iteration");
  const int strategy = csv.column("strategy");
  const int variant = csv.column("variant");
  for (const auto& [col, name] :
       {std::pair{participant, "participant"}, std::pair{iteration, "iteration"},
        std::pair{strategy, "strategy"}}) {
    if (col < 0) {
      throw InvalidData(
          fmt::format("{}: no '{}' column (needed for the strategy figures)", path, name));
    }
  }
  std::vector<TrialLabel> out;
  while (csv.next()) {
    TrialLabel t;
    t.participant = std::string(csv.field(static_cast<std::size_t>(participant)));
    if (condition >= 0) t.condition = std::string(csv.field(static_cast<std::size_t>(condition)));
    const std::string it(csv.field(static_cast<std::size_t>(iteration)));
    std::size_t used = 0;
    try {
      t.iteration = std::stoll(it, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != it.size()) {
      throw InvalidData(fmt::format("{}:{}: column 'iteration': '{}' is not a whole number", path,
                                    csv.line(), it));
    }
    t.strategy = std::string(csv.field(static_cast<std::size_t>(strategy)));
    if (variant >= 0) t.variant = std::string(csv.field(static_cast<std::size_t>(variant)));
    out.push_back(std::move(t));
  }
  return out;
}

MeanTraceAccumulator::MeanTraceAccumulator(const std::vector<TrialLabel>& labels) {
  for (const auto& t : labels) {
    auto [pos, fresh] =
        first_.try_emplace(Key{t.participant, t.condition, t.strategy, t.variant}, t.iteration);
    if (!fresh) pos->second = std::min(pos->second, t.iteration);
  }
}

bool MeanTraceAccumulator::add(const io::Trial& trial) {
  const auto f =
      first_.find(Key{trial.participant, trial.condition, trial.strategy, trial.variant});
  if (f == first_.end() || trial.times.size() < 2 || trial.pads.size() != trial.times.size()) {
    return false;
  }
  const double t0 = trial.times.front(), t1 = trial.times.back();
  std::size_t j = 0;
  for (std::size_t k = 0; k < kTracePoints; ++k) {
    const double t = t0 + (t1 - t0) * static_cast<double>(k) / (kTracePoints - 1);
    while (j + 2 < trial.times.size() && trial.times[j + 1] < t) ++j;
    const double ta = trial.times[j], tb = trial.times[j + 1];
    const double w = std::clamp((t - ta) / (tb - ta), 0.0, 1.0);
    const double pad = trial.pads[j] + w * (trial.pads[j + 1] - trial.pads[j]);
    y_[k] = 1.0 - std::fabs(pad - trial.target);  // mirrored: the true target is at 1
  }
  Sums& s = acc_[{trial.strategy, trial.variant, trial.iteration == f->second}];
  ++s.n;
  for (std::size_t k = 0; k < kTracePoints; ++k) {
    s.sum[k] += y_[k];
    s.sumsq[k] += y_[k] * y_[k];
  }
  return true;
}

std::vector<TraceCurve> MeanTraceAccumulator::curves(double conf_level) const {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<TraceCurve> out;
  for (const auto& [key, s] : acc_) {
    TraceCurve c;
    std::tie(c.strategy, c.variant, c.first_exposure) = key;
    c.trials = s.n;
    const double n = static_cast<double>(s.n);
    double q = kNaN;
    if (s.n >= 2) {
      q = boost::math::quantile(
          boost::math::complement(boost::math::students_t(n - 1), (1 - conf_level) / 2));
    }
    for (std::size_t k = 0; k < kTracePoints; ++k) {
      const double mean = s.sum[k] / n;
      const double var = s.n >= 2 ? std::max(0.0, (s.sumsq[k] - n * mean * mean) / (n - 1)) : kNaN;
      const double half = q * std::sqrt(var / n);
      c.mean.push_back(mean);
      c.conf_low.push_back(mean - half);
      c.conf_high.push_back(mean + half);
    }
    out.push_back(std::move(c));
  }
  // First exposure before later ones within a strategy (the map orders false first).
  std::stable_sort(out.begin(), out.end(), [](const TraceCurve& a, const TraceCurve& b) {
    return std::tie(a.strategy, a.variant, b.first_exposure) <
           std::tie(b.strategy, b.variant, a.first_exposure);
  });
  return out;
}

std::vector<TraceCurve> mean_traces(const std::vector<io::Trial>& trials,
                                    const std::vector<TrialLabel>& labels, double conf_level) {
  MeanTraceAccumulator acc(labels);
  for (const auto& t : trials) acc.add(t);
  return acc.curves(conf_level);
}

std::vector<TraceCurve> mean_traces(const std::vector<std::string>& log_files,
                                    io::TraceOptions options, const std::vector<TrialLabel>& labels,
                                    double conf_level) {
  MeanTraceAccumulator acc(labels);
  options.on_reject = [](const io::Rejection&) {};  // scored elsewhere; invalid trials skipped
  io::TraceReader reader(log_files, std::move(options));
  io::Trial trial;
  while (reader.next(trial)) acc.add(trial);
  return acc.curves(conf_level);
}

}  // namespace feint::metrics
