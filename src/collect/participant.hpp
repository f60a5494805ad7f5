// src/collect/participant.hpp - what a Study knows of one participant (details of the collect
// module, shared by study.cpp and rounds.cpp).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "feint/collect/study.hpp"

namespace feint::collect {

namespace detail {

// Rows carry the robot's position at each sample (robot_x, robot_y: metres), computed here from
// the round's plan, not taken from the page. A log begun before these columns existed keeps its
// layout (kLegacyLogHeader) when its study is resumed, so that no file mixes the two.
inline constexpr std::string_view kLogHeader =
    "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed,robot_x,robot_y\n";
inline constexpr std::string_view kLegacyLogHeader =
    "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
inline constexpr std::string_view kAssignmentHeader = "participant,index,condition,assigned_utc\n";
inline constexpr std::string_view kEventsHeader = "time_utc,participant,event,detail\n";

/// The round's map, true target and robot path (layouts.cpp): a pad study keeps the paper's layout
/// (target 0 is the left one); a pointer study draws or fixes its layout, and at K > 2 its true
/// target uniformly, from streams of the study's seed keyed by participant, kind and iteration.
void place_round(Round& r, const Settings& s, std::size_t index);
/// The checks of targets, layout and belief (UsageError saying what to change).
void validate_design(const Settings& s);

template <class P>
ParticipantStatus make_status(const P& p, const Settings& s) {
  ParticipantStatus st;
  st.id = p.id;
  st.condition = s.conditions[p.condition].name;
  st.practice_saved = p.saved[0];
  st.rounds_saved = p.saved[1];
  st.questionnaire_done = p.questionnaire_done;
  st.last_seen_unix = p.last_seen;
  st.interruptions = p.interruptions;
  return st;
}

}  // namespace detail

struct Study::Participant {
  std::mutex mu;  // the fields below (held briefly: never across a sync)
  std::string id;
  std::size_t index = 0;
  std::size_t condition = 0;
  std::vector<sim::Iteration> run;  // the planned analysed rounds (empty: not yet computed)
  int saved[2] = {0, 0};            // practice, main
  std::uint64_t log_size[2] = {0, 0};
  bool legacy_log[2] = {false, false};  // the log has no robot_x/robot_y (written by an older feint)
  bool questionnaire_done = false;
  bool yes_no_done = false;
  std::int64_t last_seen = 0;
  int interruptions = 0;
  std::optional<std::pair<RoundKind, int>> shown;  // round shown and not yet saved
  // One operation at a time (Study::exclusive): `busy` while one is in flight, possibly waiting
  // for its sync; the next ones wait here, in order.
  bool busy = false;
  std::deque<std::function<void()>> waiting;
};

struct Study::PendingJoin {
  std::string id;
  std::vector<Then<ParticipantStatus>> then;  // a double click: both wait for the same row
  std::shared_ptr<Participant> p;             // made when its batch is assigned
};

}  // namespace feint::collect
