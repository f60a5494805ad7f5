// The goal-inference participant fitted to a pilot by simulated moments (feint/sim/pilot_fit.hpp).
#include "feint/sim/pilot_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "feint/error.hpp"

namespace feint::sim {

namespace {

struct Person {
  bool adaptive = false;
  double early_sum = 0, later_sum = 0;
  int early_n = 0, later_n = 0;
};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double variance(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return s / static_cast<double>(v.size() - 1);
}

PilotMoments moments_of(const std::vector<Person>& people, const std::string& where) {
  std::vector<double> early, later, later_a, later_r;
  for (const auto& p : people) {
    if (p.early_n > 0) early.push_back(p.early_sum / p.early_n);
    if (p.later_n > 0) {
      const double m = p.later_sum / p.later_n;
      later.push_back(m);
      (p.adaptive ? later_a : later_r).push_back(m);
    }
  }
  if (later_a.size() < 2 || later_r.size() < 2 || early.size() < 2) {
    throw InvalidData(fmt::format(
        "{}: a pilot needs at least 2 participants with scores in each condition (adaptive: {}, "
        "random: {}) and iterations on both sides of the later-iterations boundary",
        where, later_a.size(), later_r.size()));
  }
  PilotMoments m;
  m.early = mean(early);
  m.later = mean(later);
  m.later_difference = mean(later_a) - mean(later_r);
  m.se_early = std::sqrt(variance(early) / static_cast<double>(early.size()));
  m.se_later = std::sqrt(variance(later) / static_cast<double>(later.size()));
  m.se_later_difference = std::sqrt(variance(later_a) / static_cast<double>(later_a.size()) +
                                    variance(later_r) / static_cast<double>(later_r.size()));
  m.adaptive = later_a.size();
  m.random = later_r.size();
  return m;
}

}  // namespace

PilotMoments pilot_moments(const io::ScoresTable& scores, std::size_t metric_index,
                           std::string_view adaptive, std::string_view random, int from_iteration) {
  std::map<std::pair<std::string, std::string>, Person> people;
  for (const auto& r : scores.records) {
    if (r.condition != adaptive && r.condition != random) continue;
    const auto& v = r.values.at(metric_index);
    if (!v) continue;
    Person& p = people[{r.condition, r.participant}];
    p.adaptive = r.condition == adaptive;
    if (r.iteration < from_iteration) {
      p.early_sum += *v;
      ++p.early_n;
    } else {
      p.later_sum += *v;
      ++p.later_n;
    }
  }
  std::vector<Person> list;
  for (auto& [k, p] : people) list.push_back(p);
  return moments_of(list, scores.path.empty() ? "pilot" : scores.path);
}

PilotMoments simulated_moments(const StudySettings& study, int from_iteration) {
  std::vector<Person> list;
  for (int i = 0; i < 2 * study.participants; ++i) {
    const auto p = simulate_participant(study, i);
    Person person;
    person.adaptive = p.condition == Algorithm::adaptive;
    for (const auto& tr : p.trials) {
      if (tr.iteration < from_iteration) {
        person.early_sum += tr.error;
        ++person.early_n;
      } else {
        person.later_sum += tr.error;
        ++person.later_n;
      }
    }
    list.push_back(person);
  }
  return moments_of(list, "simulated study");
}

PilotFit fit_pilot(const PilotMoments& pilot, const StudySettings& study, int from_iteration) {
  PilotFit fit;
  fit.pilot = pilot;
  fit.distance = std::numeric_limits<double>::infinity();
  auto z = [](double a, double b, double se) { return se > 0 ? (a - b) / se : 0.0; };
  auto evaluate = [&](double beta, double recognition) {
    StudySettings s = study;
    s.observer.beta = beta;
    s.observer.recognition_logodds = recognition;
    const PilotMoments m = simulated_moments(s, from_iteration);
    ++fit.candidates;
    const double d = std::pow(z(m.early, pilot.early, pilot.se_early), 2) +
                     std::pow(z(m.later_difference, pilot.later_difference, pilot.se_later_difference), 2) +
                     std::pow(z(m.later, pilot.later, pilot.se_later), 2);
    if (d < fit.distance) {
      fit.distance = d;
      fit.observer = s.observer;
      fit.fitted = m;
    }
  };
  for (double beta = 0.1; beta < 0.95; beta += 0.2) {
    for (double k = 0; k <= 10.0001; k += 2) evaluate(beta, k);
  }
  double step_beta = 0.1, step_k = 1.0;
  for (int round = 0; round < 2; ++round) {
    const double b0 = fit.observer.beta, k0 = fit.observer.recognition_logodds;
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        if (i == 0 && j == 0) continue;
        const double b = b0 + i * step_beta, k = k0 + j * step_k;
        if (b > 0 && k >= 0) evaluate(b, k);
      }
    }
    step_beta /= 2;
    step_k /= 2;
  }
  return fit;
}

}  // namespace feint::sim
