// The state of a data-collection study: assignment, rounds, validation, durable logs, rebuild
// (feint/collect/study.hpp, docs/collect.md).
#include "feint/collect/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "durable.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/rng.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::collect {

namespace fs = std::filesystem;
using detail::csv_field;

namespace {

// Rows carry the robot's position at each sample (robot_x, robot_y: metres), computed here from
// the round's plan, not taken from the page. A log begun before these columns existed keeps its
// layout (kLegacyLogHeader) when its study is resumed, so that no file mixes the two.
constexpr std::string_view kLogHeader =
    "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed,robot_x,robot_y\n";
constexpr std::string_view kLegacyLogHeader =
    "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";
constexpr std::string_view kAssignmentHeader = "participant,index,condition,assigned_utc\n";
constexpr std::string_view kEventsHeader = "time_utc,participant,event,detail\n";
// Streams of Rng::stream(seed, .): blocks of the assignment use 0, 1, ...; a participant's run and
// practice targets use offsets far above any block index.
constexpr std::uint64_t kRunStream = 1000003;
constexpr std::uint64_t kPracticeStream = 2000003;

std::size_t complete_prefix(std::string_view content) {
  const auto nl = content.rfind('\n');
  return nl == std::string_view::npos ? 0 : nl + 1;
}

/// Lines of a file's complete part (without the newline; CR stripped).
std::vector<std::string_view> lines_of(std::string_view content) {
  std::vector<std::string_view> out;
  std::size_t pos = 0;
  while (pos < content.size()) {
    const auto nl = content.find('\n', pos);
    if (nl == std::string_view::npos) break;
    std::string_view line = content.substr(pos, nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.push_back(line);
    pos = nl + 1;
  }
  return out;
}

}  // namespace

std::string_view to_string(RoundKind k) noexcept {
  return k == RoundKind::practice ? "practice" : "main";
}

Condition parse_condition(const std::string& text, double default_lambda) {
  Condition c;
  const auto colon = text.find(':');
  const std::string algo = io::to_lower(io::trim(text.substr(0, colon)));
  c.algorithm = sim::parse_algorithm(algo);
  c.lambda = default_lambda;
  c.name = std::string(sim::to_string(c.algorithm));
  if (colon != std::string::npos) {
    const auto l = io::parse_double(text.substr(colon + 1));
    if (!l || *l < 0 || *l > 1) {
      throw UsageError(fmt::format("condition '{}': lambda must be a number in [0, 1]", text));
    }
    c.lambda = *l;
    c.name += "-" + io::format_double(*l);
  }
  return c;
}

void validate(const Settings& s) {
  if (s.conditions.empty()) throw UsageError("conditions: name at least one condition");
  std::set<std::string> names;
  for (const auto& c : s.conditions) {
    if (!names.insert(c.name).second)
      throw UsageError(fmt::format("conditions: '{}' twice", c.name));
    if (c.lambda < 0 || c.lambda > 1) throw UsageError("lambda must be in [0, 1]");
  }
  if (s.iterations < 1 || s.iterations > 1000) throw UsageError("iterations must be in [1, 1000]");
  if (s.practice < 0 || s.practice > 100) throw UsageError("practice must be in [0, 100]");
  if (!(s.pad_speed > 0 && s.pad_speed <= 100)) throw UsageError("pad-speed must be in (0, 100]");
  sim::validate(s.geometry);
  if (s.items.size() != s.item_questions.size()) throw UsageError("items: one question per item");
  std::set<std::string> items;
  for (const auto& i : s.items) {
    if (!valid_participant_id(i)) {
      throw UsageError(fmt::format("item '{}': use letters, digits, '_' or '-'", i));
    }
    if (i == "participant" || i == "condition" || !items.insert(io::to_lower(i)).second) {
      throw UsageError(fmt::format("item '{}' is reserved or given twice", i));
    }
  }
  if (!s.yes_no_item.empty() && !valid_participant_id(s.yes_no_item)) {
    throw UsageError("yes-no-item: use letters, digits, '_' or '-'");
  }
  if (s.max_samples < 2) throw UsageError("max-samples must be >= 2");
}

bool valid_participant_id(const std::string& id) noexcept {
  if (id.empty() || id.size() > 64 || id.front() == '-') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

struct Study::Participant {
  std::mutex mu;  // this participant's files and counters
  std::string id;
  std::size_t index = 0;
  std::size_t condition = 0;
  std::vector<sim::Iteration> run;  // the planned analysed rounds
  int saved[2] = {0, 0};            // practice, main
  std::uint64_t log_size[2] = {0, 0};
  bool legacy_log[2] = {false, false};  // the log has no robot_x/robot_y (written by an older feint)
  bool questionnaire_done = false;
  bool yes_no_done = false;
  std::int64_t last_seen = 0;
  int interruptions = 0;
  std::optional<std::pair<RoundKind, int>> shown;  // round shown and not yet saved
};

Study::Study(fs::path dir, Settings settings)
    : dir_(std::move(dir)),
      settings_(std::move(settings)),
      committer_(std::make_unique<detail::GroupCommitter>()) {
  validate(settings_);
  std::error_code ec;
  for (const auto& sub : {fs::path("logs"), fs::path("practice"), fs::path("collect")}) {
    fs::create_directories(dir_ / sub, ec);
    if (ec)
      throw IoError(
          fmt::format("{}: cannot create folder: {}", (dir_ / sub).string(), ec.message()));
  }
  rebuild();
}

Study::~Study() = default;

fs::path Study::log_path(const std::string& id, RoundKind kind) const {
  return dir_ / (kind == RoundKind::practice ? "practice" : "logs") / (id + ".csv");
}

Round Study::plan_round(std::size_t index, std::size_t condition, RoundKind kind,
                        int iteration) const {
  Round r;
  r.kind = kind;
  r.iteration = iteration;
  if (kind == RoundKind::practice) {
    Rng rng = Rng::stream(settings_.seed, kPracticeStream + index);
    std::uint32_t side = 0;
    for (int i = 0; i < iteration; ++i) side = rng.bounded(2);
    r.strategy = sim::Strategy::optimal;
    r.variant = sim::Variant::main;
    r.target = side == 0 ? sim::Target::left : sim::Target::right;
  } else {
    const Condition& c = settings_.conditions.at(condition);
    sim::RunSettings rs;
    rs.algorithm = c.algorithm;
    rs.lambda = c.lambda;
    rs.iterations = settings_.iterations;
    Rng rng = Rng::stream(settings_.seed, kRunStream + index);
    const auto run = sim::generate_run(rs, rng);
    const auto& it = run.at(static_cast<std::size_t>(iteration - 1));
    r.strategy = it.strategy;
    r.variant = it.variant;
    r.target = it.target;
  }
  r.path = sim::trajectory(r.strategy, r.variant, r.target, settings_.geometry);
  return r;
}

void Study::record_event(const std::string& participant, const std::string& event,
                         const std::string& detail) {
  const std::string line =
      fmt::format("{},{},{},{}\n", detail::utc_now(), csv_field(participant.substr(0, 64)),
                  csv_field(event.substr(0, 32)), csv_field(detail::bounded_detail(detail)));
  committer_->append(dir_ / "collect" / "events.csv", kEventsHeader, line);
}

void Study::note_event(const std::string& participant, const std::string& event,
                       const std::string& detail) {
  std::vector<detail::GroupCommitter::Append> one;
  one.push_back({dir_ / "collect" / "events.csv", std::string(kEventsHeader),
                 fmt::format("{},{},{},{}\n", detail::utc_now(), csv_field(participant.substr(0, 64)),
                             csv_field(event.substr(0, 32)),
                             csv_field(detail::bounded_detail(detail)))});
  committer_->enqueue(std::move(one));
}

// Repairs a shared file after a crash, whatever state it was left in: empty, header only, cut in
// the header, cut mid-line. A file with no complete row after its header is set aside whole (the
// next append creates it anew with its header); otherwise only an incomplete last line is set
// aside (see replace_with_prefix). The original always goes whole to collect/damaged/.
static void keep_complete_lines(const fs::path& path, const fs::path& damaged_dir) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return;
  const std::string content = detail::read_all(path);
  std::size_t keep = complete_prefix(content);
  const auto header_end = content.find('\n');
  if (header_end == std::string::npos || keep <= header_end + 1) keep = 0;  // no complete row
  if (keep == content.size() && keep > 0) return;
  detail::replace_with_prefix(
      path, keep,
      detail::unique_aside(damaged_dir, fmt::format("{}.{}", path.filename().string(),
                                                    detail::unix_now())));
}

void Study::recover_log(Participant& p, RoundKind kind) {
  const fs::path path = log_path(p.id, kind);
  const std::string content = detail::read_all(path);
  const int k = static_cast<int>(kind);
  p.saved[k] = 0;
  p.log_size[k] = 0;
  p.legacy_log[k] = false;
  std::error_code ec;
  if (content.empty() && !fs::is_regular_file(path, ec)) return;
  const std::string where = path.string();
  std::size_t good_end = 0;
  std::size_t pos = 0;
  int current = 0;  // iteration of the rows being read
  bool current_done = true;
  double duration = 0;
  bool header = false;
  bool headerless = false;
  int complete = 0;
  while (pos < content.size()) {
    const auto nl = content.find('\n', pos);
    if (nl == std::string::npos) break;  // an incomplete last line: not part of any saved round
    std::string_view line(content.data() + pos, nl - pos);
    const std::size_t next = nl + 1;
    if (!header) {
      header = true;
      if (std::string(line) + "\n" == kLogHeader ||
          std::string(line) + "\n" == kLegacyLogHeader) {
        p.legacy_log[k] = std::string(line) + "\n" == kLegacyLogHeader;
        good_end = next;
        pos = next;
        continue;
      }
      const auto f0 = io::split_csv_line(std::string(line), ',');
      if ((f0.size() != 9 && f0.size() != 11) || f0[0] != p.id) {
        throw InvalidData(fmt::format("{}:1: not a feint collect log (unexpected header)", where));
      }
      // Rows without a header: an earlier feint collect appended to a log that a crash had left
      // empty. The rows are kept and the header is put back (below); this line is a row.
      p.legacy_log[k] = f0.size() == 9;
      headerless = true;
    }
    const auto f = io::split_csv_line(std::string(line), ',');
    if (f.size() != (p.legacy_log[k] ? 9U : 11U) || f[0] != p.id) {
      throw InvalidData(
          fmt::format("{}: a row that feint collect did not write: '{}'", where, line));
    }
    const auto it = io::parse_integer(f[2]);
    const auto t = io::parse_double(f[6]);
    if (!it || !t)
      throw InvalidData(
          fmt::format("{}: a row that feint collect did not write: '{}'", where, line));
    if (*it != current) {
      if (!current_done || *it != current + 1) {
        // A new round began before the previous one ended, or rounds are not 1, 2, ...: stop
        // here; everything from the last complete round on is set aside.
        break;
      }
      current = static_cast<int>(*it);
      current_done = false;
      duration = plan_round(p.index, p.condition, kind, current).duration();
    }
    if (!current_done && *t == duration) {
      current_done = true;
      complete = current;
      good_end = next;
    }
    pos = next;
  }
  // A log without a complete round (empty, header only, cut in its header or in its first
  // round) is set aside whole: `feint analyze` never sees a log without rows, and the next round
  // creates it anew with its header.
  if (complete == 0) good_end = 0;
  if (headerless && good_end > 0) {
    const fs::path aside = detail::unique_aside(
        dir_ / "collect" / "damaged",
        fmt::format("{}-{}-{}.csv", p.id, to_string(kind), detail::unix_now()));
    const std::string_view log_header = p.legacy_log[k] ? kLegacyLogHeader : kLogHeader;
    detail::replace_with_content(path, std::string(log_header) + content.substr(0, good_end),
                                 aside);
    record_event(p.id, "recovered",
                 fmt::format("{}: the log had no header; it was put back before the {} complete "
                             "rounds; the original ({} bytes) is in {}",
                             where, complete, content.size(), aside.string()));
    p.saved[k] = complete;
    p.log_size[k] = log_header.size() + good_end;
    return;
  }
  if (good_end < content.size() || content.empty()) {
    const fs::path aside = detail::unique_aside(
        dir_ / "collect" / "damaged",
        fmt::format("{}-{}-{}.csv", p.id, to_string(kind), detail::unix_now()));
    detail::replace_with_prefix(path, good_end, aside);
    record_event(
        p.id, "recovered",
        fmt::format("{}: kept {} complete rounds ({} bytes); the incomplete tail ({} bytes) "
                    "is in {}",
                    where, complete, good_end, content.size() - good_end, aside.string()));
  }
  p.saved[k] = complete;
  p.log_size[k] = good_end;
  // Nothing kept (not even the header): the next round starts the log anew, in the new layout.
  if (good_end == 0) p.legacy_log[k] = false;
}

void Study::rebuild() {
  const fs::path damaged = dir_ / "collect" / "damaged";
  const fs::path assignment = dir_ / "collect" / "assignment.csv";
  keep_complete_lines(assignment, damaged);
  keep_complete_lines(dir_ / "collect" / "events.csv", damaged);
  keep_complete_lines(dir_ / "questionnaire.csv", damaged);
  keep_complete_lines(dir_ / "questionnaire_yesno.csv", damaged);

  const std::string assignment_text = detail::read_all(assignment);
  const auto rows = lines_of(assignment_text);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto f = io::split_csv_line(std::string(rows[i]), ',');
    const auto index = f.size() == 4 ? io::parse_integer(f[1]) : std::nullopt;
    if (!index || *index != static_cast<long long>(i - 1) || !valid_participant_id(f[0])) {
      throw InvalidData(
          fmt::format("{}:{}: unexpected row '{}'", assignment.string(), i + 1, rows[i]));
    }
    auto p = std::make_shared<Participant>();
    p->id = f[0];
    p->index = i - 1;
    auto c = std::find_if(settings_.conditions.begin(), settings_.conditions.end(),
                          [&](const Condition& x) { return x.name == f[2]; });
    if (c == settings_.conditions.end()) {
      throw InvalidData(
          fmt::format("{}:{}: condition '{}' is not among the study's conditions; "
                      "the settings must not change during a study",
                      assignment.string(), i + 1, f[2]));
    }
    p->condition = static_cast<std::size_t>(c - settings_.conditions.begin());
    if (participants_.count(p->id)) {
      throw InvalidData(
          fmt::format("{}:{}: participant '{}' twice", assignment.string(), i + 1, p->id));
    }
    recover_log(*p, RoundKind::practice);
    recover_log(*p, RoundKind::main);
    participants_[p->id] = p;
  }
  // Log files of participants that were never assigned would be mixed into the analysis.
  for (const auto& entry : fs::directory_iterator(dir_ / "logs")) {
    const std::string stem = entry.path().stem().string();
    if (entry.path().extension() == ".csv" && valid_participant_id(stem) &&
        !participants_.count(stem)) {
      throw InvalidData(fmt::format("{}: a log of a participant not in {}", entry.path().string(),
                                    assignment.string()));
    }
  }
  auto read_done = [&](const fs::path& path, std::string_view header, bool Participant::*flag) {
    const std::string text = detail::read_all(path);
    const auto lines = lines_of(text);
    if (lines.empty()) return;
    if (std::string(lines[0]) + "\n" != header) {
      throw InvalidData(
          fmt::format("{}:1: the header differs from the configured questionnaire "
                      "items (expected '{}')",
                      path.string(), io::trim(header)));
    }
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const auto f = io::split_csv_line(std::string(lines[i]), ',');
      auto p = f.empty() ? participants_.end() : participants_.find(f[0]);
      if (p == participants_.end()) {
        throw InvalidData(fmt::format("{}:{}: unknown participant", path.string(), i + 1));
      }
      (*p->second).*flag = true;
    }
  };
  std::string qh = "participant,condition";
  for (const auto& i : settings_.items) qh += "," + i;
  read_done(dir_ / "questionnaire.csv", qh + "\n", &Participant::questionnaire_done);
  if (!settings_.yes_no_item.empty()) {
    read_done(dir_ / "questionnaire_yesno.csv",
              "participant,condition," + settings_.yes_no_item + "\n", &Participant::yes_no_done);
  }
  // The round each participant was last shown: a reload after a restart still counts as an
  // interruption when that round was never saved.
  const std::string events_text = detail::read_all(dir_ / "collect" / "events.csv");
  const auto event_lines = lines_of(events_text);
  for (std::size_t i = 1; i < event_lines.size(); ++i) {
    const auto f = io::split_csv_line(std::string(event_lines[i]), ',');
    if (f.size() != 4 || f[2] != "round_shown") continue;
    auto p = participants_.find(f[1]);
    const auto space = f[3].find(' ');
    const auto it =
        space == std::string::npos ? std::nullopt : io::parse_integer(f[3].substr(space + 1));
    if (p == participants_.end() || !it) continue;
    const RoundKind kind =
        f[3].substr(0, space) == "practice" ? RoundKind::practice : RoundKind::main;
    if (*it > p->second->saved[static_cast<int>(kind)]) {
      p->second->shown = std::make_pair(kind, static_cast<int>(*it));
    } else {
      p->second->shown.reset();
    }
  }
  if (!participants_.empty()) {
    record_event("", "restart",
                 fmt::format("state rebuilt: {} participants", participants_.size()));
  }
}

std::shared_ptr<Study::Participant> Study::find(const std::string& id) const {
  std::lock_guard lock(mu_);
  auto it = participants_.find(id);
  if (it == participants_.end()) {
    throw Rejection(404, "unknown_participant",
                    fmt::format("participant '{}' has not joined this study", id));
  }
  return it->second;
}

namespace {
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
}  // namespace

ParticipantStatus Study::join(const std::string& requested) {
  std::string id = requested;
  auto existing = [&]() -> std::shared_ptr<Participant> {
    std::lock_guard lock(mu_);
    if (id.empty()) {
      // A generated ID: random-looking, from the seed and a counter, never an existing one.
      Rng rng = Rng::stream(settings_.seed ^ static_cast<std::uint64_t>(detail::unix_now()),
                            participants_.size() + generated_);
      do {
        id = fmt::format("G{:010x}", rng() & 0xFFFFFFFFFFULL);
        ++generated_;
      } while (participants_.count(id));
    }
    if (!valid_participant_id(id)) {
      throw Rejection(
          400, "bad_participant",
          "participant IDs are 1-64 letters, digits, '_' or '-' (not starting with '-')");
    }
    auto it = participants_.find(id);
    return it == participants_.end() ? nullptr : it->second;
  };
  std::shared_ptr<Participant> p = existing();
  if (!p) {
    // New participants are assigned one at a time (the rows are numbered in order of arrival),
    // but mu_ is not held during the sync: the participants already playing are not held up.
    std::lock_guard assign(assignment_mu_);
    p = existing();  // joined meanwhile (a double click)
    if (!p) {
      p = std::make_shared<Participant>();
      p->id = id;
      {
        std::lock_guard lock(mu_);
        p->index = participants_.size();
      }
      const std::size_t c = settings_.conditions.size();
      const std::uint64_t block = p->index / c;
      std::vector<std::size_t> perm(c);
      for (std::size_t i = 0; i < c; ++i) perm[i] = i;
      Rng rng = Rng::stream(settings_.seed, block);
      sim::shuffle(perm, rng);
      p->condition = perm[p->index % c];
      const std::string& condition = settings_.conditions[p->condition].name;
      // The assignment row and its event in one commit; the participant exists (in memory too)
      // only once the row is on disk.
      std::vector<detail::GroupCommitter::Append> commit;
      commit.push_back({dir_ / "collect" / "assignment.csv", std::string(kAssignmentHeader),
                        fmt::format("{},{},{},{}\n", id, p->index, condition, detail::utc_now())});
      commit.push_back({dir_ / "collect" / "events.csv", std::string(kEventsHeader),
                        fmt::format("{},{},assigned,{}\n", detail::utc_now(), id,
                                    csv_field(condition))});
      const auto done = committer_->commit(std::move(commit));
      if (!done[0].error.empty()) throw IoError(done[0].error);
      {
        std::lock_guard lock(mu_);
        participants_[id] = p;
      }
      if (!done[1].error.empty()) throw IoError(done[1].error);
    }
  }
  std::lock_guard lock(p->mu);
  p->last_seen = detail::unix_now();
  return make_status(*p, settings_);
}

Stage Study::stage(const ParticipantStatus& s) const noexcept {
  if (s.practice_saved < settings_.practice || s.rounds_saved < settings_.iterations) {
    return (s.practice_saved == 0 && s.rounds_saved == 0 && !settings_.consent.empty())
               ? Stage::consent
               : Stage::rounds;
  }
  return s.questionnaire_done ? Stage::done : Stage::questionnaire;
}

Round Study::start_round(const std::string& id) {
  auto p = find(id);
  std::lock_guard lock(p->mu);
  p->last_seen = detail::unix_now();
  RoundKind kind = RoundKind::practice;
  int iteration = p->saved[0] + 1;
  if (p->saved[0] >= settings_.practice) {
    kind = RoundKind::main;
    iteration = p->saved[1] + 1;
    if (p->saved[1] >= settings_.iterations) {
      throw Rejection(409, "no_round_left", "every round of this participant is saved");
    }
  }
  Round r = plan_round(p->index, p->condition, kind, iteration);
  const std::string name = fmt::format("{} {}", to_string(kind), iteration);
  if (p->shown && p->shown->first == kind && p->shown->second == iteration) {
    ++p->interruptions;
    record_event(id, "interrupted",
                 name + " was shown before and not saved; shown again from its start");
  }
  p->shown = std::make_pair(kind, iteration);
  note_event(id, "round_shown", name);  // acknowledges nothing: not waited for
  return r;
}

ParticipantStatus Study::submit_round(const std::string& id, RoundKind kind, int iteration,
                                      const std::vector<PadSample>& s) {
  auto p = find(id);
  std::lock_guard lock(p->mu);
  p->last_seen = detail::unix_now();
  const int k = static_cast<int>(kind);
  const std::string name = fmt::format("{} round {}", to_string(kind), iteration);
  // Order: practice rounds first, then the analysed ones, each 1, 2, ...
  const bool practice_open = p->saved[0] < settings_.practice;
  const int limit = kind == RoundKind::practice ? settings_.practice : settings_.iterations;
  if (iteration < 1 || iteration > limit) {
    throw Rejection(409, "out_of_order", fmt::format("{} does not exist in this study", name));
  }
  if (iteration <= p->saved[k]) {
    throw Rejection(409, "duplicate", fmt::format("{} is already saved", name));
  }
  if (iteration != p->saved[k] + 1 || (kind == RoundKind::main && practice_open)) {
    throw Rejection(409, "out_of_order",
                    fmt::format("{} submitted before the rounds before it were saved", name));
  }
  const Round r = plan_round(p->index, p->condition, kind, iteration);
  // Validation: the trace as the page must have recorded it.
  auto bad = [&](const std::string& why) {
    return Rejection(422, "invalid_trace", name + ": " + why);
  };
  if (s.size() < 2) throw bad("fewer than 2 samples");
  if (s.size() > settings_.max_samples) {
    throw Rejection(
        413, "too_many_samples",
        fmt::format("{}: {} samples (at most {})", name, s.size(), settings_.max_samples));
  }
  if (s.front().t != 0 || s.front().pad != 0.5)
    throw bad("the first sample must be t = 0, pad = 0.5");
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i].t) || !std::isfinite(s[i].pad))
      throw bad(fmt::format("sample {} is not a number", i + 1));
    if (s[i].pad < 0 || s[i].pad > 1) {
      throw bad(
          fmt::format("sample {}: pad {} is outside [0, 1]", i + 1, io::format_double(s[i].pad)));
    }
    if (i == 0) continue;
    const double dt = s[i].t - s[i - 1].t;
    if (!(dt > 0)) throw bad(fmt::format("sample {}: times must increase", i + 1));
    const double dp = std::fabs(s[i].pad - s[i - 1].pad);
    if (dp > settings_.pad_speed * dt * (1 + kSpeedTolerance)) {
      throw bad(fmt::format("sample {}: the pad moved {} in {} s, faster than the pad speed {}/s",
                            i + 1, io::format_double(dp), io::format_double(dt),
                            io::format_double(settings_.pad_speed)));
    }
  }
  if (s.back().t != r.duration()) {
    throw bad(fmt::format("the last sample must be at the end of the round, t = {}",
                          io::format_double(r.duration())));
  }
  // One block of whole lines, one write, synced before the page hears of it.
  const std::string key =
      fmt::format("{},{},{},{},{},{},", id, settings_.conditions[p->condition].name, iteration,
                  sim::to_string(r.strategy), sim::to_string(r.variant), sim::to_string(r.target));
  const std::string speed = io::format_double(settings_.pad_speed);
  std::vector<double> times;
  times.reserve(s.size());
  for (const auto& x : s) times.push_back(x.t);
  const auto robot =
      sim::robot_positions(r.strategy, r.variant, r.target, settings_.geometry, times);
  std::string block;
  block.reserve(s.size() * (key.size() + 48));
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto& x = s[i];
    block += key;
    block += io::format_double(x.t);
    block += ',';
    block += io::format_double(x.pad);
    block += ',';
    block += speed;
    if (!p->legacy_log[k]) {
      block += ',';
      block += sim::format_metres(robot[i].x);
      block += ',';
      block += sim::format_metres(robot[i].y);
    }
    block += '\n';
  }
  const fs::path path = log_path(id, kind);
  if (detail::file_size_or_zero(path) != p->log_size[k]) {
    recover_log(*p, kind);  // an earlier failed write left a tail: set it aside first
    if (iteration != p->saved[k] + 1)
      throw Rejection(409, "out_of_order", name + ": state changed");
  }
  // The round and its `saved` event in one commit: synced together with whatever other rounds
  // arrived meanwhile (group commit); the event is written only when the round was.
  std::vector<detail::GroupCommitter::Append> commit;
  commit.push_back(
      {path, std::string(p->legacy_log[k] ? kLegacyLogHeader : kLogHeader), std::move(block)});
  commit.push_back({dir_ / "collect" / "events.csv", std::string(kEventsHeader),
                    fmt::format("{},{},saved,{}\n", detail::utc_now(), id,
                                csv_field(fmt::format("{} ({} samples)", name, s.size())))});
  const auto done = committer_->commit(std::move(commit));
  if (!done[0].error.empty()) throw IoError(done[0].error);
  p->log_size[k] = done[0].size;
  p->saved[k] = iteration;
  p->shown.reset();
  if (!done[1].error.empty()) throw IoError(done[1].error);  // saved; the page hears "duplicate"
  return make_status(*p, settings_);
}

ParticipantStatus Study::submit_questionnaire(const std::string& id,
                                              const std::map<std::string, std::string>& answers) {
  auto p = find(id);
  std::lock_guard lock(p->mu);
  p->last_seen = detail::unix_now();
  if (p->questionnaire_done)
    throw Rejection(409, "duplicate", "the questionnaire is already saved");
  if (p->saved[0] < settings_.practice || p->saved[1] < settings_.iterations) {
    throw Rejection(409, "out_of_order", "the questionnaire comes after the last round");
  }
  std::string row = csv_field(id) + "," + settings_.conditions[p->condition].name;
  for (const auto& item : settings_.items) {
    auto a = answers.find(item);
    const auto v = a == answers.end() ? std::nullopt : io::parse_integer(a->second);
    if (!v || *v < 1 || *v > 7) {
      throw Rejection(422, "invalid_answer",
                      fmt::format("item '{}': a whole number 1-7 is needed", item));
    }
    row += fmt::format(",{}", *v);
  }
  row += '\n';
  std::string yes_no;
  if (!settings_.yes_no_item.empty()) {
    auto a = answers.find(settings_.yes_no_item);
    if (a == answers.end() || (a->second != "yes" && a->second != "no")) {
      throw Rejection(422, "invalid_answer",
                      fmt::format("item '{}': yes or no is needed", settings_.yes_no_item));
    }
    yes_no = fmt::format("{},{},{}\n", id, settings_.conditions[p->condition].name, a->second);
  }
  for (const auto& [k, v] : answers) {
    if (k != settings_.yes_no_item &&
        std::find(settings_.items.begin(), settings_.items.end(), k) == settings_.items.end()) {
      throw Rejection(422, "invalid_answer", fmt::format("'{}' is not a questionnaire item", k));
    }
  }
  std::lock_guard qlock(questionnaire_mu_);
  if (!yes_no.empty() && !p->yes_no_done) {
    committer_->append(dir_ / "questionnaire_yesno.csv",
                   "participant,condition," + settings_.yes_no_item + "\n", yes_no);
    p->yes_no_done = true;
  }
  std::string header = "participant,condition";
  for (const auto& i : settings_.items) header += "," + i;
  committer_->append(dir_ / "questionnaire.csv", header + "\n", row);
  p->questionnaire_done = true;
  record_event(id, "questionnaire", "saved");
  return make_status(*p, settings_);
}

Study::CommitStats Study::commit_stats() const {
  return {committer_->groups(), committer_->appends()};
}

std::optional<ParticipantStatus> Study::status(const std::string& id) const {
  std::shared_ptr<Participant> p;
  {
    std::lock_guard lock(mu_);
    auto it = participants_.find(id);
    if (it == participants_.end()) return std::nullopt;
    p = it->second;
  }
  std::lock_guard lock(p->mu);
  return make_status(*p, settings_);
}

std::vector<ParticipantStatus> Study::overview() const {
  std::vector<std::shared_ptr<Participant>> all;
  {
    std::lock_guard lock(mu_);
    for (const auto& [id, p] : participants_) all.push_back(p);
  }
  std::sort(all.begin(), all.end(),
            [](const auto& a, const auto& b) { return a->index < b->index; });
  std::vector<ParticipantStatus> out;
  for (const auto& p : all) {
    std::lock_guard lock(p->mu);
    out.push_back(make_status(*p, settings_));
  }
  return out;
}

}  // namespace feint::collect
