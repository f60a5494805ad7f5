// feint/collect/study.hpp - the state of a running data-collection study (docs/collect.md).
//
// A `Study` owns the study folder while `feint collect` runs. Everything it knows is in files, so
// a server killed at any moment and restarted rebuilds the same state:
//   STUDY/collect/assignment.csv   participant, index, condition, assigned_utc (append only)
//   STUDY/logs/<participant>.csv   the analysed rounds, formats.md pad-trace layout (append only)
//   STUDY/practice/<participant>.csv  the practice rounds, same layout, outside logs/ so that
//                                  `feint analyze` never reads them
//   STUDY/questionnaire.csv        wide Likert layout: participant, condition, <item>... (1-7)
//   STUDY/questionnaire_yesno.csv  participant, condition, <yes/no item>: yes | no
//   STUDY/collect/events.csv       time_utc, participant, event, detail (audit trail)
// Every append is one write() of whole lines followed by fdatasync() before it is acknowledged.
// A round is complete when its last row has t = the round's duration (the page always ends a round
// with that sample), so a round cut short by a crash is recognised from the log alone; the log is
// then rebuilt from its complete rounds and the damaged original kept in STUDY/collect/damaged/.
//
// Rounds are chosen by the server: participant i (0-based, in order of arrival) gets the condition
// of block i / C (a permutation of the C conditions drawn from Rng::stream(seed, block)), and its
// run is sim::generate_run() under Rng::stream(seed, 1000003 + i) - the `feint simulate` code.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "feint/metrics/layout.hpp"
#include "feint/sim/selection.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::collect {

namespace detail {
class GroupCommitter;
}

/// One experimental condition: its name in the logs and the selection algorithm behind it.
struct Condition {
  std::string name;  // e.g. "adaptive", "random", "adaptive-0.3"
  sim::Algorithm algorithm = sim::Algorithm::adaptive;
  double lambda = 0.5;
};

/// Parses `adaptive`, `random`, `fixed-block`, `fixed-balanced`, optionally `:LAMBDA`
/// (`adaptive:0.3` is named `adaptive-0.3`). Throws UsageError.
Condition parse_condition(const std::string& text, double default_lambda);

/// How the participant gives their belief: the paper's 1-D pad (K = 2 only), or a point held on
/// the map (docs/collect.md "Many targets and a pointer").
enum class BeliefInput { pad, pointer };
/// The targets of a round: the same for the whole study, or drawn per round (metrics::draw_layout).
enum class LayoutMode { fixed, random };

struct Settings {
  std::vector<Condition> conditions{{"adaptive", sim::Algorithm::adaptive, 0.5},
                                    {"random", sim::Algorithm::random, 0.5}};
  int iterations = 20;     // analysed rounds per participant
  int practice = 2;        // practice rounds (optimal strategy), logged apart, not analysed
  double pad_speed = 0.8;  // pad units per second while an arrow key is held
  sim::Geometry geometry;  // trajectories (robot speed is geometry.speed)
  std::uint64_t seed = 1;  // assignment and rounds
  std::vector<std::string> items{"entertainment", "deception", "intelligence", "trust"};
  std::vector<std::string> item_questions{
      "How entertaining was the game?", "How deceptive was the robot?",
      "How intelligent did the robot seem?", "How much did you trust the robot?"};
  std::string yes_no_item = "intentional";  // empty: no yes/no question
  std::string yes_no_question = "Did the robot's movement look intentional?";
  std::string consent;              // shown before the first round when not empty
  std::string completion_url;       // the completion page links (and redirects) here when not empty
  std::size_t max_samples = 20000;  // per round
  std::size_t targets = 2;                   // K >= 2
  LayoutMode layout = LayoutMode::fixed;     // random: drawn per round from `region`
  BeliefInput belief = BeliefInput::pad;     // pointer: required when K > 2
  metrics::LayoutRegion region;              // where random layouts are drawn, and their spacing
};

/// The rectangle of the map (metres) a pointer study draws and accepts belief points in: the
/// layouts' rectangle (the fixed layout's targets, or the random layouts' region) and the start,
/// widened by 1 m on every side.
struct MapBounds {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
};
MapBounds map_bounds(const Settings& s);

/// The fixed layout of K targets: start (0, 0), the targets evenly spaced in a row at
/// target_height from x = -target_distance / 2 to +target_distance / 2 (at K = 2 the paper's).
metrics::Layout fixed_layout(const Settings& s);

/// The log's header for a study's K and belief input (pad: today's 1-D layout; pointer:
/// participant, condition, iteration, strategy, variant, target, t, belief_x, belief_y, start_x,
/// start_y, target0_x, target0_y, ..., robot_x, robot_y).
std::string log_header(const Settings& s);

/// Throws UsageError naming the setting when one is out of range.
void validate(const Settings& s);

/// Relative tolerance of the pad-speed check: a step may be at most pad_speed * dt * (1 + 1e-6),
/// the same tolerance `feint score` uses to count overspeed segments, so that an accepted round
/// never shows an overspeed segment there.
inline constexpr double kSpeedTolerance = 1e-6;

/// A participant ID is 1-64 characters of [A-Za-z0-9_-], not starting with '-'.
bool valid_participant_id(const std::string& id) noexcept;

/// A refused request: the HTTP status and a stable code (e.g. "out_of_order") for the page.
class Rejection : public std::runtime_error {
 public:
  Rejection(int status, std::string code, const std::string& message)
      : std::runtime_error(message), status_(status), code_(std::move(code)) {}
  int status() const noexcept { return status_; }
  const std::string& code() const noexcept { return code_; }

 private:
  int status_;
  std::string code_;
};

enum class RoundKind { practice, main };
std::string_view to_string(RoundKind k) noexcept;

/// One round as the server plans it.
struct Round {
  RoundKind kind = RoundKind::main;
  int iteration = 1;  // 1-based within its kind
  sim::Strategy strategy = sim::Strategy::optimal;
  sim::Variant variant = sim::Variant::main;
  sim::Target target = sim::Target::left;
  std::vector<sim::TrajectorySample> path;
  metrics::Layout layout;               // the round's map (pad studies: the paper's layout)
  std::size_t target_index = 0;         // the true target, 0..K-1 (pad: left 0, right 1)
  std::vector<sim::Point> waypoints;    // pointer studies: the robot's polyline (k_goal_waypoints)
  double duration() const noexcept { return path.empty() ? 0.0 : path.back().t; }
};

/// What comes next for a participant.
enum class Stage { consent, rounds, questionnaire, done };

struct ParticipantStatus {
  std::string id;
  std::string condition;
  int practice_saved = 0;
  int rounds_saved = 0;
  bool questionnaire_done = false;
  std::int64_t last_seen_unix = 0;  // 0 = not since the server started
  int interruptions = 0;
};

struct PadSample {
  double t = 0;
  double pad = 0.5;
};

/// A pointer study's sample: the belief as a point on the map (metres), t seconds after the trial
/// began (the participant's first touch).
struct PointerSample {
  double t = 0;
  double x = 0;
  double y = 0;
};

/// The completion of an asynchronous Study operation: the error (Rejection, IoError...) or the
/// result.
template <class T>
using Then = std::function<void(std::exception_ptr error, T result)>;

class Study {
 public:
  /// Opens (creating as needed) the study folder and rebuilds the state from its files.
  /// Throws IoError / InvalidData when the folder cannot be used.
  Study(std::filesystem::path dir, Settings settings);
  ~Study();
  Study(const Study&) = delete;
  Study& operator=(const Study&) = delete;

  const Settings& settings() const noexcept { return settings_; }
  const std::filesystem::path& dir() const noexcept { return dir_; }

  /// Joins (or re-joins) a participant; an empty `id` generates one. Throws Rejection (400) for an
  /// unsafe ID.
  ParticipantStatus join(const std::string& id);
  /// The round a participant plays next (the first not yet saved). Records `round_shown`, and
  /// `interrupted` when that round had been shown before without being saved. Throws Rejection
  /// (404 unknown participant, 409 when no round is left).
  Round start_round(const std::string& id);
  /// Validates and durably appends a finished round; returns the participant's new status.
  /// Throws Rejection: 404 unknown, 409 duplicate/out_of_order, 422 invalid trace.
  ParticipantStatus submit_round(const std::string& id, RoundKind kind, int iteration,
                                 const std::vector<PadSample>& samples);
  /// The same for a pointer study (422 invalid_trace: first t = 0, times increasing, finite,
  /// inside map_bounds, last at the round's end; 400 malformed in a pad study, and the pad form
  /// in a pointer study).
  ParticipantStatus submit_round(const std::string& id, RoundKind kind, int iteration,
                                 const std::vector<PointerSample>& samples);
  /// Appends the questionnaire answers (item -> 1..7, yes/no item -> "yes"/"no").
  ParticipantStatus submit_questionnaire(const std::string& id,
                                         const std::map<std::string, std::string>& answers);
  /// Records a rejected request or any other event (append + fdatasync).
  void record_event(const std::string& participant, const std::string& event,
                    const std::string& detail);
  /// The same, written and synced with the next group but not waited for: for audit lines that
  /// acknowledge nothing (a round shown, a client's address). A crash may lose the last of them.
  void note_event(const std::string& participant, const std::string& event,
                  const std::string& detail);

  /// The asynchronous forms, which the server uses: they never wait for a sync. `then` is called
  /// once: with the error (as the forms above throw it) or the result, after everything the
  /// answer acknowledges is synced; on the calling thread when nothing had to be written,
  /// otherwise on the group committer's completion thread. The operations of one participant
  /// run one after another, in the order they were called (a double click waits for the first
  /// save); new participants are assigned in batches, one batch per sync, numbered in order.
  void join(const std::string& id, Then<ParticipantStatus> then);
  void start_round(const std::string& id, Then<Round> then);
  void submit_round(const std::string& id, RoundKind kind, int iteration,
                    std::vector<PadSample> samples, Then<ParticipantStatus> then);
  void submit_round(const std::string& id, RoundKind kind, int iteration,
                    std::vector<PointerSample> samples, Then<ParticipantStatus> then);
  void submit_questionnaire(const std::string& id, std::map<std::string, std::string> answers,
                            Then<ParticipantStatus> then);
  void record_event(const std::string& participant, const std::string& event,
                    const std::string& detail, std::function<void(std::exception_ptr)> then);

  /// Test hook: every group's sync is preceded by this pause (a slow disk).
  void set_sync_delay(std::chrono::milliseconds delay);

  /// Syncs so far and the appends they covered (group commit: several appends per sync when
  /// requests arrive together).
  struct CommitStats {
    std::uint64_t syncs = 0;
    std::uint64_t appends = 0;
    double busy_seconds = 0;  // writing and syncing
  };
  CommitStats commit_stats() const;

  std::optional<ParticipantStatus> status(const std::string& id) const;
  std::vector<ParticipantStatus> overview() const;
  Stage stage(const ParticipantStatus& s) const noexcept;
  /// The planned round (kind, iteration) of participant `index` in `condition` (deterministic).
  Round plan_round(std::size_t index, std::size_t condition, RoundKind kind, int iteration) const;

 private:
  struct Participant;
  struct PendingJoin;
  std::shared_ptr<Participant> find(const std::string& id) const;
  void rebuild();
  void recover_log(Participant& p, RoundKind kind);
  std::filesystem::path log_path(const std::string& id, RoundKind kind) const;
  /// plan_round() from the participant's cached run and the cached trajectories.
  Round plan_for(Participant& p, RoundKind kind, int iteration) const;
  /// The common part of both submit_round forms: order, recovery, then `rows` (validates and
  /// formats the round's rows; legacy: the log has the old pad layout) in one commit.
  using RowsOf =
      std::function<std::string(const Round&, const std::string& condition, bool legacy)>;
  void submit_rows(const std::string& id, RoundKind kind, int iteration, std::size_t samples,
                   RowsOf rows, Then<ParticipantStatus> then);
  std::string event_line(const std::string& participant, const std::string& event,
                         const std::string& detail) const;
  /// Runs `op` when no other operation of `p` is in flight; `op` must call release(p) once done.
  void exclusive(const std::shared_ptr<Participant>& p, std::function<void()> op);
  void release(const std::shared_ptr<Participant>& p);
  /// Assigns the joins waiting (called with mu_ held, no batch in flight; unlocks it).
  void assign_waiting(std::unique_lock<std::mutex>& lock);

  std::filesystem::path dir_;
  Settings settings_;
  mutable std::mutex mu_;  // participants_, the joins waiting or in flight, id generation
  std::map<std::string, std::shared_ptr<Participant>> participants_;
  std::deque<PendingJoin> joins_waiting_;
  std::shared_ptr<std::vector<PendingJoin>> joins_in_flight_;  // null: none
  std::uint64_t generated_ = 0;
  /// The robot's path of every (strategy, variant, target), computed once.
  std::map<std::tuple<int, int, int>, std::vector<sim::TrajectorySample>> paths_;
  std::unique_ptr<detail::GroupCommitter> committer_;  // every durable append goes through it
};

}  // namespace feint::collect
