// A study's condition design, declared or read off the data (see feint/models/condition_design.hpp).
#include "feint/models/condition_design.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdint>
#include <map>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::models {

std::optional<ConditionDesign> parse_condition_design(std::string_view text) {
  const std::string d = io::to_lower(std::string(io::trim(text)));
  if (d.empty()) return std::nullopt;
  if (d == "between") return ConditionDesign::between;
  if (d == "within") return ConditionDesign::within;
  throw UsageError(fmt::format(
      "--design '{}': expected between (each participant saw one condition) or within (each "
      "participant saw every condition)",
      text));
}

std::string_view to_string(ConditionDesign design) noexcept {
  return design == ConditionDesign::within ? "within" : "between";
}

namespace {

// Where a participant's trials first appear in each condition (condition -> line).
struct Seen {
  std::map<std::string, std::uint64_t> first_line;
};

std::string plural(std::size_t n, const char* one, const char* many) { return n == 1 ? one : many; }

// "P07 (adaptive only)" or "P07 (adaptive, random; not fixed)".
std::string incomplete_entry(const std::string& id, const Seen& s) {
  std::string saw;
  for (const auto& [c, _] : s.first_line) saw += (saw.empty() ? "" : ", ") + c;
  return fmt::format("{} ({}{})", id, saw, s.first_line.size() == 1 ? " only" : "");
}

// "file:12" or, for rows without a line (trials scored in memory), "file".
std::string where(const std::string& source, std::uint64_t line) {
  return line > 0 ? fmt::format("{}:{}", source, line) : source;
}
std::string at_line(std::uint64_t line) { return line > 0 ? fmt::format(" (line {})", line) : std::string(); }

// The first participant with two conditions: (id, its two conditions with their lines).
[[noreturn]] void refuse_between(const std::string& source, const std::string& id, const Seen& s) {
  auto a = s.first_line.begin(), b = std::next(a);
  if (a->second > b->second) std::swap(a, b);
  throw InvalidData(fmt::format(
      "{}: participant '{}' has trials in condition '{}'{} and in '{}'{}, but the design is "
      "declared between participants (design = \"between\"): set design = \"within\" in feint.toml "
      "(or --design within) when every participant saw every condition, or correct the "
      "participant ids",
      where(source, b->second), id, b->first, at_line(b->second), a->first, at_line(a->second)));
}

}  // namespace

namespace {

// Who saw which conditions, in the order of the rows.
struct Tally {
  std::vector<std::string> order;                    // participants, first appearance
  std::map<std::string, Seen> seen;
  std::map<std::string, std::size_t> per_condition;  // condition -> participants
  std::size_t several = 0, every = 0;                // in more than one / in every condition
  const std::string* first_several = nullptr;
  const std::string* first_single = nullptr;
  const std::string* first_incomplete = nullptr;  // saw fewer than every condition
};

Tally tally(std::span<const Observation> observations) {
  Tally t;
  for (const Observation& o : observations) {
    if (o.condition.empty()) continue;
    auto [it, fresh] = t.seen.try_emplace(o.participant);
    if (fresh) t.order.push_back(o.participant);
    if (it->second.first_line.emplace(o.condition, o.line).second) ++t.per_condition[o.condition];
  }
  for (const auto& id : t.order) {
    const std::size_t k = t.seen[id].first_line.size();
    if (k > 1) {
      ++t.several;
      if (!t.first_several) t.first_several = &id;
    } else if (!t.first_single) {
      t.first_single = &id;
    }
    if (k == t.per_condition.size())
      ++t.every;
    else if (!t.first_incomplete)
      t.first_incomplete = &id;
  }
  return t;
}

// The design (declared, or read off the data) and its note; throws where the data contradict it.
void decide(Tally& t, std::optional<ConditionDesign> declared, const std::string& source, DesignCheck& c) {
  const std::size_t conditions = t.per_condition.size(), n = t.order.size();
  if (declared == ConditionDesign::between) {
    if (t.first_several) refuse_between(source, *t.first_several, t.seen[*t.first_several]);
    c.note = "conditions between participants (declared: design = \"between\")";
  } else if (declared == ConditionDesign::within) {
    if (conditions > 1 && t.several == 0)
      throw InvalidData(fmt::format(
          "{}: the design is declared within participants (design = \"within\") but no participant "
          "has trials in two conditions ({} participants, each in one of {} conditions): set design = "
          "\"between\" when each participant saw one condition, or check the participant ids",
          source, n, conditions));
    c.note = fmt::format("conditions within participants (declared: design = \"within\"; {} of {} "
                         "participants saw every condition)", t.every, n);
  } else if (t.several == 0) {
    if (conditions > 1)
      c.note = fmt::format("conditions between participants (read off the data: each of the {} participants "
                           "saw one condition)", n);
  } else if (t.every == n) {
    c.design = ConditionDesign::within;
    c.note = fmt::format("conditions within participants (read off the data: each of the {} participants saw "
                         "{} conditions)", n, conditions == 2 ? std::string("both") : "all " + std::to_string(conditions));
  } else {
    const Seen& s = t.seen[*t.first_several];
    const auto later = std::max_element(s.first_line.begin(), s.first_line.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
    // The participant to name beside: one who saw a single condition, else (three or more
    // conditions, everyone in two or more) one who saw fewer than all of them.
    const std::string& fewer = t.first_single ? *t.first_single : *t.first_incomplete;
    const std::size_t k = t.seen[fewer].first_line.size();
    throw InvalidData(fmt::format(
        "{}: participant '{}' has trials in {} conditions but participant '{}'{} in {} ({} "
        "of {} participants saw more than one): declare the design in feint.toml (or with "
        "--design): design = \"within\" when every participant was meant to see every condition "
        "(those who did not are then named and left out of the paired tests), design = "
        "\"between\" when each was meant to see one (the ids in two conditions must then be "
        "corrected)",
        where(source, later->second), *t.first_several, s.first_line.size(), fewer,
        at_line(t.seen[fewer].first_line.begin()->second),
        k == 1 ? std::string("one only") : fmt::format("{} of the {} only", k, conditions), t.several, n));
  }
}

}  // namespace

DesignCheck check_condition_design(std::span<const Observation> observations,
                                   std::optional<ConditionDesign> declared, const std::string& source) {
  Tally t = tally(observations);
  DesignCheck c;
  c.declared = declared.has_value();
  c.design = declared.value_or(ConditionDesign::between);
  if (t.seen.empty()) return c;
  decide(t, declared, source, c);
  const std::size_t conditions = t.per_condition.size();
  if (c.design == ConditionDesign::within) {
    for (const auto& id : t.order)
      if (t.seen[id].first_line.size() < conditions) c.incomplete.push_back(incomplete_entry(id, t.seen[id]));
    if (!c.incomplete.empty())
      c.warnings.push_back(fmt::format(
          "{} {} did not see every condition and {} left out of the paired tests (the mixed model "
          "keeps their trials): {}",
          c.incomplete.size(), plural(c.incomplete.size(), "participant", "participants"),
          plural(c.incomplete.size(), "is", "are"), fmt::join(c.incomplete, ", ")));
  } else {
    for (const auto& [cond, count] : t.per_condition)
      if (count == 1 && conditions > 1) c.single_participant_conditions.push_back(cond);
  }
  if (!c.single_participant_conditions.empty())
    c.warnings.push_back(fmt::format(
        "{} {} {}: {} variance between participants cannot be estimated, so the tests that need it "
        "are not computable",
        c.single_participant_conditions.size() == 1 ? "condition" : "conditions",
        fmt::join(c.single_participant_conditions, ", "),
        c.single_participant_conditions.size() == 1 ? "has one participant only" : "have one participant each",
        c.single_participant_conditions.size() == 1 ? "its" : "their"));
  return c;
}

}  // namespace feint::models
