// feint/sim/study.hpp - a simulated user study (selection.md "Simulated studies").
//
// N simulated participants per condition (by default adaptive, lambda 0.5, and random; any two or
// more of the selection algorithms) each watch a run of N iterations chosen by their condition's
// algorithm (generate_run), with a fresh Observer; their pad traces are written as pad-trace logs
// (formats.md), one gzipped CSV per participant, and a wide 1-7 Likert questionnaire
// (entertainment, deception, intelligence, trust) is derived from each participant's mean error
// plus noise. Participant i (0-based; the first N in the first condition, the next N in the second,
// ...) draws everything from Rng::stream(seed, i).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "feint/io/output_folder.hpp"
#include "feint/metrics/layout.hpp"
#include "feint/sim/observer.hpp"
#include "feint/sim/pointer_participant.hpp"
#include "feint/sim/selection.hpp"
#include "feint/sim/trajectory.hpp"

namespace feint::sim {

/// Conditions in order: adaptive, random (the seed paper's).
inline constexpr std::array<Algorithm, 2> kStudyConditions = {Algorithm::adaptive, Algorithm::random};

struct StudySettings {
  int participants = 20;  // per condition (within: in all)
  /// The conditions compared: two or more distinct selection algorithms, named in the logs by
  /// to_string(Algorithm) (adaptive, random, fixed-block, fixed-balanced).
  std::vector<Algorithm> conditions{kStudyConditions.begin(), kStudyConditions.end()};
  /// The conditions' names in the logs and the questionnaire, one per condition, distinct; empty:
  /// the algorithms' names. Naming lets a study run one algorithm under several labels (e.g. three
  /// conditions all `random`: a null study of three conditions).
  std::vector<std::string> condition_names;
  /// Conditions within participants: each participant sees every condition, one block of
  /// `iterations` each, in an order rotated by participant (participant i, 0-based, sees conditions
  /// i mod C, i+1 mod C, ...: with the two default conditions, adaptive first for P01, P03, ... and
  /// random first for P02, P04, ...), with one observer whose memory carries over from block to
  /// block (the carry-over that counterbalancing balances). No questionnaire is simulated.
  bool within = false;
  int iterations = 20;
  double lambda = 0.5;    // of the adaptive condition
  std::uint64_t seed = 1;
  Geometry geometry;
  ObserverParams observer = goal_inference_observer();
  /// Targets on the map, K >= 2 (`--targets`). With 2 and a fixed layout the study is the paper's
  /// (pad-trace logs); otherwise each participant points (sim/pointer_participant.hpp) and the logs
  /// are logs of K targets and a pointer (formats.md).
  int targets = 2;
  /// `--layout`: false = fixed (row_layout: K targets evenly spaced on the paper's row); true =
  /// drawn per round from `region` with metrics::draw_layout, seeded per participant and round.
  bool random_layout = false;
  metrics::LayoutRegion region;
};

/// True when the study's participants point on a map (K > 2 targets, or a layout drawn per round).
bool is_pointer_study(const StudySettings& settings) noexcept;

/// Round `round` (0-based over all of a participant's rounds) of participant `index`: row_layout,
/// or draw_layout(Rng::stream(seed ^ 0x6c61796f7574, index * 2^20 + round), region, K).
metrics::Layout round_layout(const StudySettings& settings, int index, int round);

/// The error of a participant who guesses on `layout`: it points at a target drawn uniformly at
/// random and holds it, with the true target drawn uniformly as the study draws it,
///     (1/K^2) sum_true sum_k |G_k - G_true| / s,     s = metrics::layout_scale(layout).
/// At K = 2 it is 0.5 exactly (the undecided pad's error); for 3 targets equally spaced on a row
/// 4/9 (docs/simulation.md "References of a study of K targets").
double guessing_error(const metrics::Layout& layout);

/// The study's reference for error, R_error: guessing_error of its fixed layout, or the mean of
/// guessing_error over every round of every participant (round_layout) when the layouts are drawn
/// per round: the study's own layouts, so no sampling error. 0.5 for the paper's study.
double guessing_error_reference(const StudySettings& settings);

struct TrialRecord {
  int iteration = 0;  // 1-based, within its condition
  int block = 1;      // within designs: 1 or 2, the order in which the participant saw the condition
  Strategy strategy = Strategy::optimal;
  Variant variant = Variant::main;
  Target target = Target::left;
  std::vector<PadSample> pad;
  double error = 0;  // trial_error() of the trace (pointer studies: the belief point's error)
  // Pointer studies (is_pointer_study): the round's map, the true target's index, the pointer and
  // the robot at each sample.
  metrics::Layout layout;
  std::size_t target_index = 0;
  std::vector<PointerSample> pointer;
  std::vector<TrajectorySample> robot;
};

struct ParticipantRecord {
  std::string id;  // P01, P02, ...
  Algorithm condition = Algorithm::adaptive;
  std::string condition_name = "adaptive";  // as the logs name it (StudySettings::condition_names)
  std::vector<TrialRecord> trials;
  double mean_error = 0;
  std::array<int, 4> likert{};  // entertainment, deception, intelligence, trust (1-7)
  /// The yes/no question "was the robot deceiving you on purpose?" (questionnaire_yesno.csv): yes
  /// with probability 1 / (1 + exp(-(deception - 4.5))), drawn last so that every other number of
  /// a participant is the same as before the question was simulated.
  bool intentional = false;
};

/// Error of a trial (paper eq. 3), for checks on simulated data: the time-weighted mean of
/// |T - pad(t)| over the window [t0 + trim tau, t_end - trim tau] of the piecewise-linear trace
/// (trapezoids; exact because T is 0 or 1 and the pad stays in [0, 1]).
double trial_error(const std::vector<PadSample>& pad, double target, double trim = 0.05);

/// The name of condition `index` (StudySettings::condition_names, else the algorithm's name).
std::string condition_name(const StudySettings& settings, std::size_t index);

/// Throws UsageError unless there are two or more conditions, each named once (names: letters,
/// digits, '-', '_' and '.'), and as many names as conditions when they are named.
void validate_conditions(const StudySettings& settings);

/// Participant `index` (0-based over all conditions) of a study.
ParticipantRecord simulate_participant(const StudySettings& settings, int index);

/// Participant `index` (0-based) of a within-participant study (settings.within): one record per
/// condition, in the order seen, all with the participant's id; everything is drawn from
/// Rng::stream(seed, index).
std::vector<ParticipantRecord> simulate_participant_within(const StudySettings& settings, int index);

/// Writes DIR/logs/<participant>.csv.gz (columns participant, condition, iteration, strategy,
/// variant, target, t, pad, pad_speed, robot_x, robot_y: the robot's position in metres at each
/// sample, formats.md "Robot path") and DIR/questionnaire.csv (participant, condition,
/// entertainment, deception, intelligence, trust). DIR is written as one unit
/// (feint/io/output_folder.hpp): everything goes into a staging folder that replaces DIR when
/// complete, so a run never mixes with an earlier one. A DIR that exists and is not empty is
/// refused (UsageError) unless `replace` is set, and even then only when it holds nothing but an
/// earlier `feint simulate study`'s files. Returns the participants (for a summary). Throws
/// IoError when a file cannot be written.
std::vector<ParticipantRecord> write_study(const StudySettings& settings, const std::string& dir,
                                           bool replace = false,
                                           std::string_view tool_version = "unknown");

/// The study's feint.toml (written as DIR/feint.toml): the comparison of its conditions, and
/// confusion on the raw scale with the paper's references (a pointer study: error's reference is
/// guessing_error_reference), so that `feint analyze DIR` compares the conditions with the scores
/// and references on one scale, with no setting made by hand.
std::string study_toml(const StudySettings& settings, std::string_view tool_version);

/// `feint simulate study` as the writer of its folder (manifest .feint-simulate.json; --replace).
io::FolderWriter study_folder_writer(bool replace);

}  // namespace feint::sim
