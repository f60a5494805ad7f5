// A simulated user study (see feint/sim/study.hpp and docs/simulation.md).
#include "feint/sim/study.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/metrics/belief_point.hpp"
#include "feint/sim/k_goal_paths.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::sim {

double trial_error(const std::vector<PadSample>& pad, double target, double trim) {
  if (pad.size() < 2) return std::nan("");
  const double t0 = pad.front().t;
  const double tau = pad.back().t - t0;
  const double lo = t0 + trim * tau;
  const double hi = pad.back().t - trim * tau;
  if (!(hi > lo)) return std::nan("");
  double integral = 0;
  for (std::size_t i = 1; i < pad.size(); ++i) {
    const double a = pad[i - 1].t, b = pad[i].t;
    const double s = std::max(a, lo), e = std::min(b, hi);
    if (!(e > s)) continue;
    auto at = [&](double t) { return pad[i - 1].pad + (pad[i].pad - pad[i - 1].pad) * (t - a) / (b - a); };
    integral += (std::abs(target - at(s)) + std::abs(target - at(e))) / 2 * (e - s);
  }
  return integral / (hi - lo);
}

namespace {

int likert(double value) { return static_cast<int>(std::clamp(std::lround(value), 1L, 7L)); }

std::string participant_id(int index, int total) {
  const int width = std::max(2, static_cast<int>(std::to_string(total).size()));
  return fmt::format("P{:0{}}", index + 1, width);
}

}  // namespace

bool is_pointer_study(const StudySettings& settings) noexcept {
  return settings.targets != 2 || settings.random_layout;
}

metrics::Layout round_layout(const StudySettings& settings, int index, int round) {
  if (settings.targets < 2)
    throw UsageError(fmt::format("--targets {}: a study needs 2 or more targets", settings.targets));
  const auto k = static_cast<std::size_t>(settings.targets);
  if (!settings.random_layout) return row_layout(k, settings.geometry);
  // Its own stream per participant and round: the layouts do not depend on the participant's answers.
  Rng rng = Rng::stream(settings.seed ^ 0x6c61796f7574ULL,
                        (static_cast<std::uint64_t>(index) << 20) + static_cast<std::uint64_t>(round));
  return metrics::draw_layout(rng, settings.region, k);
}

double guessing_error(const metrics::Layout& layout) {
  if (layout.targets.size() < 2) throw UsageError("guessing_error: a layout needs 2 or more targets");
  const double s = metrics::layout_scale(layout);
  double sum = 0;
  for (const auto& truth : layout.targets)
    for (const auto& guess : layout.targets) sum += metrics::distance(guess, truth) / s;
  const auto k = static_cast<double>(layout.targets.size());
  return sum / (k * k);
}

namespace {

// The study's people and the rounds each plays (within: every condition's block).
struct StudyRounds {
  int people = 0;
  int rounds = 0;
};
StudyRounds study_rounds(const StudySettings& settings) noexcept {
  const auto conditions = static_cast<int>(settings.conditions.size());
  if (settings.within) return {settings.participants, conditions * settings.iterations};
  return {conditions * settings.participants, settings.iterations};
}

}  // namespace

double guessing_error_reference(const StudySettings& settings) {
  if (!is_pointer_study(settings)) return 0.5;
  if (!settings.random_layout) return guessing_error(round_layout(settings, 0, 0));
  const StudyRounds n = study_rounds(settings);
  double sum = 0;
  for (int i = 0; i < n.people; ++i)
    for (int r = 0; r < n.rounds; ++r) sum += guessing_error(round_layout(settings, i, r));
  return sum / (static_cast<double>(n.people) * n.rounds);
}

namespace {

// A round of a pointer study: the round's map, the true target (drawn uniformly), the robot's path
// for the strategy (sim::k_goal_paths) and the pointer of the participant, who recognises the
// strategy with `observer`'s memory.
void watch_round(const StudySettings& settings, int index, int round, const Iteration& it, const Observer& observer,
                 TrialRecord& tr, Rng& rng) {
  tr.layout = round_layout(settings, index, round);
  tr.target_index = rng.bounded(static_cast<std::uint32_t>(settings.targets));
  KGoalPathSettings ks;
  ks.geometry = settings.geometry;
  ks.observer.beta = settings.observer.beta;
  tr.robot = k_goal_trajectory(tr.layout, tr.target_index, it.strategy,
                               it.strategy == Strategy::optimal ? Variant::main : it.variant, ks);
  // The participant learns as the pad's does: its memory of the strategies shown so far.
  const PointerRecognition learning{tr.target_index, observer.recognition(it.strategy, it.variant)};
  tr.pointer = watch_pointer(tr.robot, tr.layout, settings.observer, rng, learning);
  std::vector<double> times;
  std::vector<metrics::MapPoint> points;
  for (const auto& q : tr.pointer) {
    times.push_back(q.t);
    points.push_back({q.x, q.y});
  }
  tr.error = metrics::score_belief_points(times, points, tr.layout, tr.target_index, std::nullopt, {}).error;
}

// One block of a participant: the condition's run, watched by `observer` (rounds numbered from
// `round0` for the layouts of a pointer study).
ParticipantRecord watch_block(const StudySettings& settings, Algorithm condition, int block, Observer& observer,
                              Rng& rng, int index, int round0) {
  ParticipantRecord p;
  p.condition = condition;
  RunSettings run;
  run.algorithm = condition;
  run.lambda = settings.lambda;
  run.iterations = settings.iterations;
  const std::vector<Iteration> its = generate_run(run, rng);
  double sum = 0;
  for (std::size_t i = 0; i < its.size(); ++i) {
    const auto& it = its[i];
    TrialRecord tr;
    tr.iteration = static_cast<int>(i) + 1;
    tr.block = block;
    tr.strategy = it.strategy;
    tr.variant = it.variant;
    tr.target = it.target;
    if (is_pointer_study(settings)) {
      watch_round(settings, index, round0 + static_cast<int>(i), it, observer, tr, rng);
    } else {
      const auto path = trajectory(it.strategy, it.variant, it.target, settings.geometry);
      tr.pad = observer.watch(path, it.strategy, it.variant, it.target, settings.geometry, rng);
      tr.error = trial_error(tr.pad, it.target == Target::left ? 0.0 : 1.0);
    }
    observer.remember(it.strategy, it.variant);
    sum += tr.error;
    p.trials.push_back(std::move(tr));
  }
  p.mean_error = sum / static_cast<double>(its.size());
  return p;
}

}  // namespace

std::string condition_name(const StudySettings& settings, std::size_t index) {
  return settings.condition_names.empty() ? std::string(to_string(settings.conditions.at(index)))
                                          : settings.condition_names.at(index);
}

void validate_conditions(const StudySettings& settings) {
  const auto& conditions = settings.conditions;
  if (conditions.size() < 2)
    throw UsageError(fmt::format("--conditions: {} condition(s) given; a study compares two or more "
                                 "(e.g. --conditions adaptive,random,fixed-block)", conditions.size()));
  if (!settings.condition_names.empty() && settings.condition_names.size() != conditions.size())
    throw UsageError(fmt::format("--conditions: {} names for {} conditions", settings.condition_names.size(),
                                 conditions.size()));
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    const std::string name = condition_name(settings, i);
    const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' || c == '.';
    });
    if (!plain)
      throw UsageError(fmt::format("--conditions: the name '{}' is not a plain name (letters, digits, '-', '_', '.')",
                                   name));
    for (std::size_t j = 0; j < i; ++j)
      if (condition_name(settings, j) == name)
        throw UsageError(fmt::format("--conditions: '{}' is named twice; name each condition once (NAME=ALGORITHM "
                                     "runs one algorithm under several names)",
                                     name));
  }
}

ParticipantRecord simulate_participant(const StudySettings& settings, int index) {
  validate(settings.geometry);
  validate_conditions(settings);
  if (settings.participants < 1) throw UsageError("participants per condition must be >= 1");
  const int people = static_cast<int>(settings.conditions.size()) * settings.participants;
  if (index < 0 || index >= people) throw UsageError("participant index out of range");
  Rng rng = Rng::stream(settings.seed, static_cast<std::uint64_t>(index));
  Observer observer(settings.observer);
  const auto c = static_cast<std::size_t>(index / settings.participants);
  ParticipantRecord p = watch_block(settings, settings.conditions[c], 1, observer, rng, index, 0);
  p.condition_name = condition_name(settings, c);
  p.id = participant_id(index, people);
  // Likert answers: centred near the paper's adaptive-condition means (entertainment 6.1,
  // deception 4.8, intelligence 6.8, trust 2.2), rising (trust: falling) with the participant's
  // mean error; Gaussian noise; rounded and kept within 1-7 (a rating scale has no other values).
  const double e = p.mean_error - 0.45;
  p.likert = {likert(5.9 + 2.0 * e + 0.7 * rng.normal()), likert(4.7 + 6.0 * e + 0.8 * rng.normal()),
              likert(6.3 + 2.0 * e + 0.6 * rng.normal()), likert(2.4 - 3.0 * e + 0.8 * rng.normal())};
  p.intentional = rng.uniform() < 1 / (1 + std::exp(-(p.likert[1] - 4.5)));
  return p;
}


std::vector<ParticipantRecord> simulate_participant_within(const StudySettings& settings, int index) {
  validate(settings.geometry);
  validate_conditions(settings);
  if (settings.participants < 1) throw UsageError("participants must be >= 1");
  if (index < 0 || index >= settings.participants) throw UsageError("participant index out of range");
  Rng rng = Rng::stream(settings.seed, static_cast<std::uint64_t>(index));
  Observer observer(settings.observer);
  // Orders rotated by participant: each condition is seen in each position equally often when the
  // number of participants is a multiple of the number of conditions.
  const std::size_t n = settings.conditions.size();
  std::vector<ParticipantRecord> blocks;
  for (std::size_t b = 0; b < n; ++b) {
    const std::size_t c = (b + static_cast<std::size_t>(index)) % n;
    blocks.push_back(watch_block(settings, settings.conditions[c], static_cast<int>(b) + 1, observer, rng, index,
                                 static_cast<int>(b) * settings.iterations));
    blocks.back().id = participant_id(index, settings.participants);
    blocks.back().condition_name = condition_name(settings, c);
  }
  return blocks;
}

namespace {

// A folder that `feint simulate study` wrote before it wrote a manifest: logs/ with P*.csv.gz and
// questionnaire.csv.
bool is_legacy_study_output(std::string_view name) {
  if (name == "logs/" || name == "questionnaire.csv") return true;
  constexpr std::string_view prefix = "logs/P", suffix = ".csv.gz";
  if (name.size() <= prefix.size() + suffix.size() || name.substr(0, prefix.size()) != prefix ||
      name.substr(name.size() - suffix.size()) != suffix) {
    return false;
  }
  const auto digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

namespace {

// The conditions as feint.toml and the logs name them, joined by `sep`.
std::string condition_names(const StudySettings& settings, std::string_view sep) {
  std::string out;
  for (std::size_t c = 0; c < settings.conditions.size(); ++c) {
    if (!out.empty()) out += sep;
    out += condition_name(settings, c);
  }
  return out;
}

}  // namespace

namespace {

// The references feint.toml gives: the paper's for the pad; for a pointer study, error's reference
// is the error of guessing on the study's layouts (docs/simulation.md "References of a study of K
// targets").
// A reference as the tables print it: 4 decimals, trailing zeros dropped (4/9 -> "0.4444", 0.5 -> "0.5").
std::string reference_text(double r) {
  std::string t = fmt::format("{:.4f}", r);
  while (t.back() == '0') t.pop_back();
  if (t.back() == '.') t.pop_back();
  return t;
}

std::string references_toml(const StudySettings& settings) {
  if (!is_pointer_study(settings)) return "metric = [\"error=0.5\", \"confusion=0.95@raw\"]\n";
  const StudyRounds n = study_rounds(settings);
  const double r = guessing_error_reference(settings);
  const std::string over =
      settings.random_layout
          ? fmt::format("the study's {} layouts (every round of every participant)", n.people * n.rounds)
          : std::string("the study's fixed layout (exact)");
  return fmt::format(
      "# References on the layout scale s (the largest distance between two targets; at K = 2 the pad's\n"
      "# unit). error: the error of a participant who guesses (points at a target drawn uniformly and\n"
      "# holds it), R = mean of (1/K^2) sum_true sum_k |G_k - G_true| / s\n"
      "# over {}; at K = 2 the paper's 0.5. Written to 4 decimals, as a reference a paper states\n"
      "# (exactly {}).\n"
      "# confusion: the paper's 0.95, kept: a held guess never reverses (confusion 0), so guessing gives\n"
      "# no reference for it.\n"
      "metric = [\"error={}\", \"confusion=0.95@raw\"]\n",
      over, io::format_double(r), reference_text(r));
}

// What feint.toml says of a pointer study (nothing for the paper's study: its file is unchanged).
std::string pointer_toml(const StudySettings& settings) {
  if (!is_pointer_study(settings)) return {};
  return fmt::format(
      "\n# {} targets, {}.\n"
      "# The participants point on the map (logs of K targets and a pointer, docs/formats.md): error\n"
      "# and confusion are in layout scales (the largest distance between two targets;\n"
      "# docs/many-targets.md).\n",
      settings.targets,
      settings.random_layout ? "placed per round at random (--layout random)" : "in a fixed row (--layout fixed)");
}

}  // namespace

std::string study_toml(const StudySettings& settings, std::string_view tool_version) {
  const bool two = settings.conditions.size() == 2;
  const std::string each = two ? "both conditions" : "every condition";
  const std::string design =
      settings.within
          ? fmt::format("{} participants, each in {} (counterbalanced blocks of {} iterations)",
                        settings.participants, each, settings.iterations)
          : fmt::format("{} participants per condition, {} iterations", settings.participants, settings.iterations);
  // Two conditions: Table 1 compares them; three or more: the models' omnibus test of condition and
  // its pairs (Table 1 describes each condition).
  const std::string compare =
      two ? fmt::format("# The study compares its two conditions (Table 1 two-sample, the models, the "
                        "questionnaire).\ncompare = \"{}\"\n\n",
                        condition_names(settings, ","))
          : fmt::format("# The study compares its {} conditions ({}): the models' test of condition, then each\n"
                        "# pair. Table 1 describes each condition against the references.\n\n",
                        settings.conditions.size(), condition_names(settings, ", "));
  return fmt::format(
      "# The design of this simulated study, written by feint simulate study (feint {}), read by\n"
      "# `feint analyze` (names are its options without the dashes; the command line wins).\n"
      "# {}, lambda {} (adaptive), seed {}.\n\n"
      "# {}\n"
      "design = \"{}\"\n\n"
      "{}"
      "# Confusion on the paper's scale (eq. 4 without normalisation), where the paper's reference\n"
      "# 0.95 lies: the scores and the reference are on one scale (docs/metrics.md).\n"
      "confusion-norm = \"raw\"\n"
      "{}",
      tool_version, design, io::format_double(settings.lambda), settings.seed,
      settings.within ? fmt::format("Each participant saw {}: conditions within participants (paired tests).", each)
                      : "Each participant saw one condition: conditions between participants.",
      settings.within ? "within" : "between", compare, references_toml(settings)) + pointer_toml(settings);
}

io::FolderWriter study_folder_writer(bool replace) {
  io::FolderWriter w;
  w.command = "feint simulate study";
  w.manifest = ".feint-simulate.json";
  w.option = "-o";
  w.legacy_output = &is_legacy_study_output;
  w.ask_before_replacing = true;
  w.replace = replace;
  w.replace_option = "--replace";
  return w;
}

namespace {

// A participant's pad-trace log: every trial of its blocks, with the robot's position at each pad
// sample (formats.md "Robot path", to 0.1 mm); within designs add the block column.
std::string log_text(const std::vector<ParticipantRecord>& blocks, const StudySettings& settings) {
  const std::string pad_speed = io::format_double(settings.observer.pad_speed);
  std::string text = settings.within ? "participant,condition,block,iteration,strategy,variant,target,t,pad,"
                                       "pad_speed,robot_x,robot_y\n"
                                     : "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed,"
                                       "robot_x,robot_y\n";
  std::vector<double> times;
  for (const auto& p : blocks) {
    const std::string& cond = p.condition_name;
    for (const auto& tr : p.trials) {
      const std::string key =
          settings.within ? fmt::format("{},{},{},{},{},{},{},", p.id, cond, tr.block, tr.iteration,
                                        to_string(tr.strategy), to_string(tr.variant), to_string(tr.target))
                          : fmt::format("{},{},{},{},{},{},", p.id, cond, tr.iteration, to_string(tr.strategy),
                                        to_string(tr.variant), to_string(tr.target));
      times.clear();
      for (const auto& s : tr.pad) times.push_back(s.t - tr.pad.front().t);
      const auto robot = robot_positions(tr.strategy, tr.variant, tr.target, settings.geometry, times);
      for (std::size_t k = 0; k < tr.pad.size(); ++k) {
        const auto& s = tr.pad[k];
        text += key;
        text += io::format_double(s.t);
        text += ',';
        text += io::format_double(s.pad);
        text += ',';
        text += pad_speed;
        text += ',';
        text += format_metres(robot[k].x);
        text += ',';
        text += format_metres(robot[k].y);
        text += '\n';
      }
    }
  }
  return text;
}

// A participant's log of K targets and a pointer (formats.md "Logs of K targets and a pointer"):
// metres to 0.1 mm, the true target's index, the round's layout on every row.
std::string pointer_log_text(const std::vector<ParticipantRecord>& blocks, const StudySettings& settings) {
  std::string text = settings.within ? "participant,condition,block,iteration,strategy,variant,target,t,"
                                     : "participant,condition,iteration,strategy,variant,target,t,";
  text += "belief_x,belief_y,start_x,start_y,";
  for (int k = 0; k < settings.targets; ++k) text += fmt::format("target{}_x,target{}_y,", k, k);
  text += "robot_x,robot_y\n";
  for (const auto& p : blocks) {
    for (const auto& tr : p.trials) {
      std::string key = settings.within ? fmt::format("{},{},{},{},{},{},{},", p.id, p.condition_name, tr.block,
                                                      tr.iteration, to_string(tr.strategy), to_string(tr.variant),
                                                      tr.target_index)
                                        : fmt::format("{},{},{},{},{},{},", p.id, p.condition_name, tr.iteration,
                                                      to_string(tr.strategy), to_string(tr.variant), tr.target_index);
      std::string layout = format_metres(tr.layout.start.x) + ',' + format_metres(tr.layout.start.y) + ',';
      for (const auto& g : tr.layout.targets) layout += format_metres(g.x) + ',' + format_metres(g.y) + ',';
      for (std::size_t i = 0; i < tr.pointer.size(); ++i) {
        const auto& q = tr.pointer[i];
        text += key;
        text += io::format_double(q.t - tr.pointer.front().t);
        text += ',';
        text += format_metres(q.x);
        text += ',';
        text += format_metres(q.y);
        text += ',';
        text += layout;
        text += format_metres(tr.robot[i].x);
        text += ',';
        text += format_metres(tr.robot[i].y);
        text += '\n';
      }
    }
  }
  return text;
}

// DIR/logs/<id>.csv.gz, written under a temporary name and renamed into place.
void write_log(const std::filesystem::path& logs, const std::string& id, const std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = logs / (id + ".csv.gz");
  const fs::path tmp = logs / ("." + id + ".csv.gz.tmp");
  gzFile gz = gzopen(tmp.c_str(), "wb9");
  if (gz == nullptr) throw IoError(fmt::format("{}: cannot open for writing", tmp.string()));
  const int written = gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
  const int closed = gzclose(gz);
  if (written != static_cast<int>(text.size()) || closed != Z_OK) {
    fs::remove(tmp, ec);
    throw IoError(fmt::format("{}: write failed", tmp.string()));
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw IoError(fmt::format("{}: cannot rename into place", target.string()));
  }
}

// The questionnaires: one row per participant (between) or per participant and condition (within).
void write_questionnaires(const std::vector<ParticipantRecord>& all, io::OutputFolder& folder) {
  std::string q = "participant,condition,entertainment,deception,intelligence,trust\n";
  for (const auto& p : all) {
    q += fmt::format("{},{},{},{},{},{}\n", p.id, p.condition_name, p.likert[0], p.likert[1],
                     p.likert[2], p.likert[3]);
  }
  io::write_file_atomically(folder.path("questionnaire.csv"), q);
  std::string yes_no = "participant,condition,intentional\n";
  for (const auto& p : all)
    yes_no += fmt::format("{},{},{}\n", p.id, p.condition_name, p.intentional ? "yes" : "no");
  io::write_file_atomically(folder.path("questionnaire_yesno.csv"), yes_no);
}

// The questionnaires of a within-participants study, answered after each condition: one row per
// participant and condition (in the order the blocks were seen). The answers follow that block's
// mean error as simulate_participant's do, drawn from streams of their own (seed ^ "question",
// row) so that the logs are the same as without a questionnaire.
void write_within_questionnaires(const StudySettings& settings, std::vector<ParticipantRecord>& blocks,
                                 io::OutputFolder& folder) {
  constexpr std::uint64_t kQuestionnaireStreams = 0x7175657374696f6eULL;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Rng rng = Rng::stream(settings.seed ^ kQuestionnaireStreams, i);
    ParticipantRecord& p = blocks[i];
    const double e = p.mean_error - 0.45;
    p.likert = {likert(5.9 + 2.0 * e + 0.7 * rng.normal()), likert(4.7 + 6.0 * e + 0.8 * rng.normal()),
                likert(6.3 + 2.0 * e + 0.6 * rng.normal()), likert(2.4 - 3.0 * e + 0.8 * rng.normal())};
    p.intentional = rng.uniform() < 1 / (1 + std::exp(-(p.likert[1] - 4.5)));
  }
  write_questionnaires(blocks, folder);
}

}  // namespace

std::vector<ParticipantRecord> write_study(const StudySettings& settings, const std::string& dir,
                                           bool replace, std::string_view tool_version) {
  namespace fs = std::filesystem;
  io::OutputFolder folder(dir, {}, study_folder_writer(replace));
  const fs::path logs = folder.staging() / "logs";
  std::error_code ec;
  fs::create_directories(logs, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create directory: {}", logs.string(), ec.message()));
  std::vector<ParticipantRecord> all;
  validate_conditions(settings);
  const int people =
      settings.within ? settings.participants : static_cast<int>(settings.conditions.size()) * settings.participants;
  for (int i = 0; i < people; ++i) {
    std::vector<ParticipantRecord> blocks = settings.within ? simulate_participant_within(settings, i)
                                                            : std::vector{simulate_participant(settings, i)};
    write_log(logs, blocks.front().id,
              is_pointer_study(settings) ? pointer_log_text(blocks, settings) : log_text(blocks, settings));
    for (auto& p : blocks) {
      for (auto& tr : p.trials) {  // the traces are on disk; keep the summary small
        tr.pad.clear();
        tr.pointer.clear();
        tr.robot.clear();
      }
      all.push_back(std::move(p));
    }
  }
  if (settings.within)
    write_within_questionnaires(settings, all, folder);
  else
    write_questionnaires(all, folder);
  io::write_file_atomically(folder.path("feint.toml"), study_toml(settings, tool_version));
  folder.commit(tool_version);
  return all;
}

}  // namespace feint::sim
