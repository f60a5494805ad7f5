#include "feint/io/participants.hpp"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "feint/io/number.hpp"

namespace feint::io {

namespace {

std::string listed(const std::vector<std::string>& ids) {
  constexpr std::size_t kShown = 10;
  std::vector<std::string> shown(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(std::min(ids.size(), kShown)));
  std::string out = fmt::format("{}", fmt::join(shown, ", "));
  if (ids.size() > kShown) out += fmt::format(" and {} more", ids.size() - kShown);
  return out;
}

}  // namespace

ParticipantComparison compare_participants(const std::vector<std::string>& log_ids,
                                           const std::vector<std::string>& questionnaire_ids) {
  std::set<std::string> logs, quest;
  for (const auto& id : log_ids) logs.emplace(trim(id));
  for (const auto& id : questionnaire_ids) quest.emplace(trim(id));
  ParticipantComparison c;
  std::set_difference(logs.begin(), logs.end(), quest.begin(), quest.end(),
                      std::back_inserter(c.only_in_logs));
  std::set_difference(quest.begin(), quest.end(), logs.begin(), logs.end(),
                      std::back_inserter(c.only_in_questionnaire));
  c.in_both = logs.size() - c.only_in_logs.size();
  return c;
}

std::string ParticipantComparison::message() const {
  if (matches()) return {};
  std::vector<std::string> parts;
  if (!only_in_logs.empty()) {
    parts.push_back(fmt::format("{} in the logs only ({})", only_in_logs.size(), listed(only_in_logs)));
  }
  if (!only_in_questionnaire.empty()) {
    parts.push_back(fmt::format("{} in the questionnaire only ({})", only_in_questionnaire.size(),
                                listed(only_in_questionnaire)));
  }
  parts.push_back(fmt::format("{} in both", in_both));
  std::string out = fmt::format("participant ids differ between the logs and the questionnaire: {}",
                                fmt::join(parts, "; "));
  // The commonest cause: the same person written in two cases (P01 / p01).
  for (const auto& a : only_in_logs) {
    for (const auto& b : only_in_questionnaire) {
      if (to_lower(a) == to_lower(b)) {
        return out + fmt::format(" (ids are compared exactly: {} and {} are two people)", a, b);
      }
    }
  }
  return out;
}

}  // namespace feint::io
