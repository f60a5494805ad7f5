#include "feint/analysis/hypotheses.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"

namespace feint::analysis {

std::vector<Hypothesis> default_hypotheses(const std::string& a, const std::string& b) {
  // The seed paper's two questions: people stay deceived longer (higher error, more confusion)
  // when strategies are picked adaptively, and they judge the robot differently afterwards.
  return {
      {"H1",
       fmt::format("People stay deceived longer under {} than under {} selection (higher error and "
                   "confusion).",
                   a, b),
       {"error", "confusion"},
       "greater",
       false,
       {a, b}},
      {"H2", fmt::format("The questionnaire answers differ between {} and {}.", a, b),
       {"questionnaire"},
       "two-sided",
       false,
       {a, b}},
  };
}

namespace {

std::vector<std::string> split_commas(std::string_view s) {
  std::vector<std::string> out;
  while (!s.empty()) {
    const auto comma = s.find(',');
    const std::string part(io::trim(s.substr(0, comma)));
    if (!part.empty()) out.push_back(part);
    if (comma == std::string_view::npos) break;
    s.remove_prefix(comma + 1);
  }
  return out;
}

void set_key(Hypothesis& h, const std::string& key, const std::string& value, const std::string& text) {
  auto bad = [&](const char* expected) {
    return UsageError(fmt::format("hypothesis '{}': {} '{}' is not {}", text, key, value, expected));
  };
  if (key == "statement") {
    h.statement = value;
  } else if (key == "measures") {
    h.measures = split_commas(value);
    for (const auto& m : h.measures)
      if (m != "error" && m != "confusion" && m != "questionnaire") throw bad("a list of error, confusion, questionnaire");
  } else if (key == "direction") {
    if (value != "greater" && value != "less" && value != "two-sided") throw bad("greater, less or two-sided");
    h.direction = value;
  } else if (key == "confirmatory") {
    if (value != "true" && value != "false") throw bad("true or false");
    h.confirmatory = value == "true";
  } else {
    throw UsageError(fmt::format("hypothesis '{}': unknown key '{}' (statement, measures, direction, "
                                 "confirmatory)", text, key));
  }
}

}  // namespace

std::vector<Hypothesis> default_hypotheses(const std::vector<std::string>& conditions) {
  std::string names;
  for (std::size_t i = 0; i < conditions.size(); ++i)
    names += (i == 0 ? "" : i + 1 == conditions.size() ? " and " : ", ") + conditions[i];
  return {
      {"H1", fmt::format("Error and confusion differ among the conditions {}.", names),
       {"error", "confusion"},
       "two-sided",
       false,
       {}},
      {"H2", fmt::format("The questionnaire answers differ among the conditions {}.", names),
       {"questionnaire"},
       "two-sided",
       false,
       {}},
  };
}

std::vector<Hypothesis> parse_hypotheses(const std::vector<std::string>& settings, const std::string& a,
                                         const std::string& b) {
  return parse_hypotheses(settings, default_hypotheses(a, b));
}

std::vector<Hypothesis> parse_hypotheses(const std::vector<std::string>& settings, std::vector<Hypothesis> hs) {
  for (const auto& text : settings) {
    const auto colon = text.find(':');
    const auto eq = text.find('=', colon == std::string::npos ? 0 : colon);
    if (colon == std::string::npos || eq == std::string::npos || colon == 0) {
      throw UsageError(fmt::format("hypothesis '{}': expected ID:KEY=VALUE, e.g. H1:confirmatory=true "
                                   "(feint.toml: [hypotheses.H1] confirmatory = true)", text));
    }
    const std::string id(io::trim(std::string_view(text).substr(0, colon)));
    const std::string key(io::trim(std::string_view(text).substr(colon + 1, eq - colon - 1)));
    const std::string value(io::trim(std::string_view(text).substr(eq + 1)));
    auto it = std::find_if(hs.begin(), hs.end(), [&](const Hypothesis& h) { return h.id == id; });
    if (it == hs.end()) {
      hs.push_back({id, "", {}, "two-sided", false, {}});
      it = hs.end() - 1;
    }
    set_key(*it, key, value, text);
  }
  for (const auto& h : hs)
    if (h.statement.empty() || h.measures.empty())
      throw UsageError(fmt::format("hypothesis {}: give its statement and measures ([hypotheses.{}] "
                                   "statement = \"...\", measures = [\"error\"])", h.id, h.id));
  return hs;
}

}  // namespace feint::analysis
