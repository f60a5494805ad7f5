#include "feint/models/design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "feint/error.hpp"

namespace feint::models {

std::vector<std::size_t> WideDesign::group_sizes() const {
  std::vector<std::size_t> sizes(conditions.size(), 0);
  for (std::size_t g : group) ++sizes[g];
  return sizes;
}

namespace {

struct Person {
  std::size_t condition = 0;
  std::uint64_t first_line = 0;
  std::map<long long, std::optional<double>> values;
};

struct People {
  std::vector<std::string> order;  // participants in order of first appearance
  std::unordered_map<std::string, Person> by_name;
  std::map<long long, std::size_t> with_value;  // iteration -> number of values present
};

// One pass over the rows: conditions in order of first appearance (into d), each participant's
// values, and how many values each iteration has. A participant in two conditions stops here.
People collect_people(std::span<const Observation> observations, const std::string& source,
                      WideDesign& d) {
  People people;
  for (const Observation& o : observations) {
    auto c = std::find(d.conditions.begin(), d.conditions.end(), o.condition);
    const auto ci = static_cast<std::size_t>(c - d.conditions.begin());
    if (c == d.conditions.end()) d.conditions.push_back(o.condition);
    auto [it, fresh] = people.by_name.try_emplace(o.participant);
    if (fresh) {
      it->second.condition = ci;
      it->second.first_line = o.line;
      people.order.push_back(o.participant);
    } else if (it->second.condition != ci) {
      throw InvalidData(fmt::format(
          "{}:{}: participant '{}' is in condition '{}' but line {} put it in '{}'; the mixed "
          "ANOVA needs each participant in exactly one condition (condition is between "
          "participants)",
          source, o.line, o.participant, o.condition, it->second.first_line,
          d.conditions[it->second.condition]));
    }
    it->second.values[o.iteration] = o.value;
    auto& count = people.with_value[o.iteration];
    if (o.value) ++count;
  }
  return people;
}

// The iterations (ascending); each needs some value, and there must be at least two.
void take_iterations(const People& people, const std::string& source, const std::string& metric,
                     WideDesign& d) {
  for (const auto& [iteration, count] : people.with_value) {
    if (count == 0) {
      throw InvalidData(fmt::format(
          "{}: metric '{}': iteration {} has no value for any participant; drop the iteration "
          "or fill in its values",
          source, metric, iteration));
    }
    d.iterations.push_back(iteration);
  }
  if (d.iterations.size() < 2) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': only one iteration ({}); a repeated-measures ANOVA needs at least two",
        source, metric, d.iterations.front()));
  }
}

bool has_every_iteration(const Person& p, const std::vector<long long>& iterations) {
  for (long long it : iterations) {
    auto v = p.values.find(it);
    if (v == p.values.end() || !v->second) return false;
  }
  return true;
}

// Complete cases, grouped by condition (order of first appearance within each); the rest are
// excluded.
void take_complete_cases(const People& people, const std::string& source, const std::string& metric,
                         WideDesign& d) {
  for (std::size_t g = 0; g < d.conditions.size(); ++g) {
    for (const std::string& name : people.order) {
      const Person& p = people.by_name.at(name);
      if (p.condition != g) continue;
      if (!has_every_iteration(p, d.iterations)) {
        d.excluded.push_back(name);
        continue;
      }
      d.participants.push_back(name);
      d.group.push_back(g);
      for (long long it : d.iterations) d.y.push_back(*p.values.at(it));
    }
  }
  if (d.participants.empty()) {
    throw InvalidData(fmt::format(
        "{}: metric '{}': no participant has a value for every iteration ({} to {}); the "
        "repeated-measures ANOVA uses complete cases only (feint model keeps incomplete ones)",
        source, metric, d.iterations.front(), d.iterations.back()));
  }
}

[[noreturn]] void throw_empty_condition(const People& people, const std::string& source,
                                        const std::string& metric, const WideDesign& d,
                                        std::size_t g) {
  std::vector<std::string> who;
  for (const std::string& name : people.order)
    if (people.by_name.at(name).condition == g) who.push_back(name);
  std::string list;
  for (std::size_t i = 0; i < who.size() && i < 5; ++i) list += (i ? ", " : "") + who[i];
  if (who.size() > 5) list += fmt::format(", ... ({} in all)", who.size());
  throw InvalidData(fmt::format(
      "{}: metric '{}': every participant of condition '{}' ({}) lacks a value for some "
      "iteration, so the complete-case ANOVA has nobody left in '{}' and would become an "
      "analysis of the other condition(s) only. Fill in the missing values, use `feint model` "
      "(it keeps incomplete participants), or ask for the analysis without '{}' with "
      "--drop-empty-conditions",
      source, metric, d.conditions[g], list, d.conditions[g], d.conditions[g]));
}

// A condition whose participants were all excluded: stop (as afex), or drop it when asked and
// renumber the groups of the conditions kept.
void drop_empty_conditions_or_throw(const People& people, const std::string& source,
                                    const std::string& metric, bool drop_empty_conditions,
                                    WideDesign& d) {
  std::vector<std::size_t> sizes(d.conditions.size(), 0);
  for (std::size_t g : d.group) ++sizes[g];
  for (std::size_t g = 0; g < d.conditions.size(); ++g) {
    if (sizes[g] > 0) continue;
    if (!drop_empty_conditions) throw_empty_condition(people, source, metric, d, g);
    d.dropped_conditions.push_back(d.conditions[g]);
  }
  std::vector<std::size_t> remap(d.conditions.size(), 0);
  std::vector<std::string> kept;
  for (std::size_t g = 0; g < d.conditions.size(); ++g) {
    remap[g] = kept.size();
    if (sizes[g] > 0) kept.push_back(d.conditions[g]);
  }
  for (auto& g : d.group) g = remap[g];
  d.conditions = std::move(kept);
}

void require_variance(const std::string& source, const std::string& metric, const WideDesign& d) {
  const auto [lo, hi] = std::minmax_element(d.y.begin(), d.y.end());
  if (*lo == *hi) {
    throw InvalidData(fmt::format(
        "{}: metric '{}' has no variance: every value of the {} complete participants is {}; an "
        "ANOVA of a constant is undefined",
        source, metric, d.participants.size(), *lo));
  }
}

}  // namespace

WideDesign make_wide_design(std::span<const Observation> observations, const std::string& metric,
                            const std::string& source, bool drop_empty_conditions) {
  WideDesign d;
  d.source = source;
  d.metric = metric;
  if (observations.empty()) {
    throw InvalidData(fmt::format("{}: metric '{}': no data rows", source, metric));
  }
  const People people = collect_people(observations, source, d);
  take_iterations(people, source, metric, d);
  take_complete_cases(people, source, metric, d);
  drop_empty_conditions_or_throw(people, source, metric, drop_empty_conditions, d);
  require_variance(source, metric, d);
  return d;
}

}  // namespace feint::models
