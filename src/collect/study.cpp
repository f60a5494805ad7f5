// The state of a data-collection study: assignment, rounds, validation, durable logs, rebuild
// (feint/collect/study.hpp, docs/collect.md).
#include "feint/collect/study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "durable.hpp"
#include "participant.hpp"
#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/rng.hpp"
#include "feint/sim/robot_path.hpp"

namespace feint::collect {

namespace fs = std::filesystem;
using detail::csv_field;
using detail::kEventsHeader;
using detail::kLegacyLogHeader;
using detail::kLogHeader;
using detail::make_status;

namespace {

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
  detail::validate_design(s);
}

bool valid_participant_id(const std::string& id) noexcept {
  if (id.empty() || id.size() > 64 || id.front() == '-') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

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
  // The robot's paths: one per (strategy, variant, target), the same for every participant
  // (pointer studies plan each round's path on its own layout).
  for (const auto st : {sim::Strategy::exaggerating, sim::Strategy::switching,
                        sim::Strategy::ambiguous, sim::Strategy::optimal})
    for (const auto v : {sim::Variant::main, sim::Variant::v2})
      for (const auto t : {sim::Target::left, sim::Target::right}) {
        if (st == sim::Strategy::optimal && v == sim::Variant::v2) continue;  // has one version
        paths_[{static_cast<int>(st), static_cast<int>(v), static_cast<int>(t)}] =
            sim::trajectory(st, v, t, settings_.geometry);
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
  if (settings_.belief == BeliefInput::pad)
    r.path = paths_.at({static_cast<int>(r.strategy), static_cast<int>(r.variant),
                        static_cast<int>(r.target)});
  detail::place_round(r, settings_, index);
  return r;
}

Round Study::plan_for(Participant& p, RoundKind kind, int iteration) const {
  if (kind == RoundKind::practice) return plan_round(p.index, p.condition, kind, iteration);
  if (p.run.empty()) {  // the run is drawn once per participant, not at every round
    const Condition& c = settings_.conditions.at(p.condition);
    sim::RunSettings rs;
    rs.algorithm = c.algorithm;
    rs.lambda = c.lambda;
    rs.iterations = settings_.iterations;
    Rng rng = Rng::stream(settings_.seed, kRunStream + p.index);
    p.run = sim::generate_run(rs, rng);
  }
  Round r;
  r.kind = kind;
  r.iteration = iteration;
  const auto& it = p.run.at(static_cast<std::size_t>(iteration - 1));
  r.strategy = it.strategy;
  r.variant = it.variant;
  r.target = it.target;
  if (settings_.belief == BeliefInput::pad)
    r.path = paths_.at({static_cast<int>(r.strategy), static_cast<int>(r.variant),
                        static_cast<int>(r.target)});
  detail::place_round(r, settings_, p.index);
  return r;
}

std::string Study::event_line(const std::string& participant, const std::string& event,
                              const std::string& detail) const {
  return fmt::format("{},{},{},{}\n", detail::utc_now(), csv_field(participant.substr(0, 64)),
                     csv_field(event.substr(0, 32)), csv_field(detail::bounded_detail(detail)));
}

void Study::record_event(const std::string& participant, const std::string& event,
                         const std::string& detail) {
  committer_->append(dir_ / "collect" / "events.csv", kEventsHeader,
                     event_line(participant, event, detail));
}

void Study::record_event(const std::string& participant, const std::string& event,
                         const std::string& detail, std::function<void(std::exception_ptr)> then) {
  std::vector<detail::GroupCommitter::Append> one;
  one.push_back({dir_ / "collect" / "events.csv", std::string(kEventsHeader),
                 event_line(participant, event, detail)});
  committer_->commit_async(std::move(one), [then = std::move(then)](auto r) {
    then(r[0].error.empty() ? nullptr : std::make_exception_ptr(IoError(r[0].error)));
  });
}

void Study::note_event(const std::string& participant, const std::string& event,
                       const std::string& detail) {
  std::vector<detail::GroupCommitter::Append> one;
  one.push_back({dir_ / "collect" / "events.csv", std::string(kEventsHeader),
                 event_line(participant, event, detail)});
  committer_->enqueue(std::move(one));
}

void Study::set_sync_delay(std::chrono::milliseconds delay) { committer_->set_sync_delay(delay); }

void Study::exclusive(const std::shared_ptr<Participant>& p, std::function<void()> op) {
  {
    std::lock_guard lock(p->mu);
    if (p->busy) {
      p->waiting.push_back(std::move(op));
      return;
    }
    p->busy = true;
  }
  op();
}

void Study::release(const std::shared_ptr<Participant>& p) {
  std::function<void()> next;
  {
    std::lock_guard lock(p->mu);
    if (p->waiting.empty()) {
      p->busy = false;
      return;
    }
    next = std::move(p->waiting.front());  // stays busy: handed on to the next operation
    p->waiting.pop_front();
  }
  next();
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

namespace {

/// The fields of a row under a pointer study's header.
std::size_t pointer_columns(const std::string& header) {
  return static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
}

/// What a participant's round log holds, read row by row.
struct LogScan {
  std::size_t good_end = 0;  ///< bytes up to the end of the last complete round (or the header)
  int complete = 0;          ///< complete rounds
  bool headerless = false;   ///< rows without a header (see is_log_header)
};

/// Whether the first line of a log is its header; `legacy` is set from its layout.
/// `pointer` is a pointer study's header ("" for a pad study): a study's logs have one layout.
bool is_log_header(std::string_view line, const std::string& id, const std::string& where,
                   bool& legacy, const std::string& pointer) {
  const std::string with_newline = std::string(line) + "\n";
  if (!pointer.empty()) {
    if (with_newline == pointer) return true;
    const auto f0 = io::split_csv_line(std::string(line), ',');
    if (f0.size() != pointer_columns(pointer) || f0[0] != id) {
      throw InvalidData(fmt::format(
          "{}:1: not a log of this study (expected the header '{}'): a pad log, or a study of "
          "another number of targets; the settings must not change during a study",
          where, io::trim(pointer)));
    }
    return false;  // rows without a header, as below
  }
  if (with_newline == kLogHeader || with_newline == kLegacyLogHeader) {
    legacy = with_newline == kLegacyLogHeader;
    return true;
  }
  const auto f0 = io::split_csv_line(std::string(line), ',');
  if ((f0.size() != 9 && f0.size() != 11) || f0[0] != id) {
    throw InvalidData(fmt::format("{}:1: not a feint collect log (unexpected header)", where));
  }
  // Rows without a header: an earlier feint collect appended to a log that a crash had left
  // empty. The rows are kept and the header is put back (by recover_log); this line is a row.
  legacy = f0.size() == 9;
  return false;
}

// A round is complete at its row with t = its duration (round_duration(iteration)); rounds must
// be 1, 2, ... Throws InvalidData for a row feint collect did not write.
LogScan scan_log(const std::string& content, const std::string& id, const std::string& where,
                 bool& legacy, const std::string& pointer,
                 const std::function<double(int)>& round_duration) {
  const std::size_t pointer_fields = pointer.empty() ? 0 : pointer_columns(pointer);
  LogScan scan;
  std::size_t pos = 0;
  int current = 0;  // iteration of the rows being read
  bool current_done = true;
  double duration = 0;
  bool header = false;
  while (pos < content.size()) {
    const auto nl = content.find('\n', pos);
    if (nl == std::string::npos) break;  // an incomplete last line: not part of any saved round
    std::string_view line(content.data() + pos, nl - pos);
    const std::size_t next = nl + 1;
    if (!header) {
      header = true;
      if (is_log_header(line, id, where, legacy, pointer)) {
        scan.good_end = next;
        pos = next;
        continue;
      }
      scan.headerless = true;
    }
    const auto f = io::split_csv_line(std::string(line), ',');
    if (f.size() != (pointer.empty() ? (legacy ? 9U : 11U) : pointer_fields) || f[0] != id) {
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
      duration = round_duration(current);
    }
    if (!current_done && *t == duration) {
      current_done = true;
      scan.complete = current;
      scan.good_end = next;
    }
    pos = next;
  }
  return scan;
}

/// Where a damaged round log is set aside.
fs::path log_aside(const fs::path& dir, const std::string& id, RoundKind kind) {
  return detail::unique_aside(
      dir / "collect" / "damaged",
      fmt::format("{}-{}-{}.csv", id, to_string(kind), detail::unix_now()));
}

}  // namespace

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
  const std::string header = log_header(settings_);
  const std::string pointer = settings_.belief == BeliefInput::pointer ? header : std::string();
  const LogScan scan =
      scan_log(content, p.id, where, p.legacy_log[k], pointer,
               [&](int iteration) { return plan_for(p, kind, iteration).duration(); });
  const int complete = scan.complete;
  // A log without a complete round (empty, header only, cut in its header or in its first
  // round) is set aside whole: `feint analyze` never sees a log without rows, and the next round
  // creates it anew with its header.
  const std::size_t good_end = complete == 0 ? 0 : scan.good_end;
  if (scan.headerless && good_end > 0) {
    const fs::path aside = log_aside(dir_, p.id, kind);
    const std::string_view log_header = p.legacy_log[k] ? kLegacyLogHeader : header;
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
    const fs::path aside = log_aside(dir_, p.id, kind);
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

namespace {

/// Row i of collect/assignment.csv (its line i + 1), whose index must be i - 1.
struct AssignmentRow {
  std::string id;
  std::size_t condition = 0;  ///< index into the settings' conditions
};

AssignmentRow parse_assignment_row(std::string_view row, std::size_t i, const fs::path& assignment,
                                   const std::vector<Condition>& conditions) {
  const auto f = io::split_csv_line(std::string(row), ',');
  const auto index = f.size() == 4 ? io::parse_integer(f[1]) : std::nullopt;
  if (!index || *index != static_cast<long long>(i - 1) || !valid_participant_id(f[0])) {
    throw InvalidData(fmt::format("{}:{}: unexpected row '{}'", assignment.string(), i + 1, row));
  }
  auto c = std::find_if(conditions.begin(), conditions.end(),
                        [&](const Condition& x) { return x.name == f[2]; });
  if (c == conditions.end()) {
    throw InvalidData(
        fmt::format("{}:{}: condition '{}' is not among the study's conditions; "
                    "the settings must not change during a study",
                    assignment.string(), i + 1, f[2]));
  }
  return {f[0], static_cast<std::size_t>(c - conditions.begin())};
}

// Log files of participants that were never assigned would be mixed into the analysis.
// (Templates over the participants: Study::Participant is private to Study.)
template <class Participants>
void check_no_stray_logs(const fs::path& logs, const Participants& participants,
                         const fs::path& assignment) {
  for (const auto& entry : fs::directory_iterator(logs)) {
    const std::string stem = entry.path().stem().string();
    if (entry.path().extension() == ".csv" && valid_participant_id(stem) &&
        !participants.count(stem)) {
      throw InvalidData(fmt::format("{}: a log of a participant not in {}", entry.path().string(),
                                    assignment.string()));
    }
  }
}

/// Sets `flag` of every participant with a row in the questionnaire file `path`.
template <class Participants, class Flag>
void read_done(const fs::path& path, std::string_view header, Participants& participants,
               Flag flag) {
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
    auto p = f.empty() ? participants.end() : participants.find(f[0]);
    if (p == participants.end()) {
      throw InvalidData(fmt::format("{}:{}: unknown participant", path.string(), i + 1));
    }
    (*p->second).*flag = true;
  }
}

// The round each participant was last shown: a reload after a restart still counts as an
// interruption when that round was never saved.
template <class Participants>
void read_rounds_shown(const fs::path& events, Participants& participants) {
  const std::string events_text = detail::read_all(events);
  const auto event_lines = lines_of(events_text);
  for (std::size_t i = 1; i < event_lines.size(); ++i) {
    const auto f = io::split_csv_line(std::string(event_lines[i]), ',');
    if (f.size() != 4 || f[2] != "round_shown") continue;
    auto p = participants.find(f[1]);
    const auto space = f[3].find(' ');
    const auto it =
        space == std::string::npos ? std::nullopt : io::parse_integer(f[3].substr(space + 1));
    if (p == participants.end() || !it) continue;
    const RoundKind kind =
        f[3].substr(0, space) == "practice" ? RoundKind::practice : RoundKind::main;
    if (*it > p->second->saved[static_cast<int>(kind)]) {
      p->second->shown = std::make_pair(kind, static_cast<int>(*it));
    } else {
      p->second->shown.reset();
    }
  }
}

}  // namespace

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
    const AssignmentRow row = parse_assignment_row(rows[i], i, assignment, settings_.conditions);
    auto p = std::make_shared<Participant>();
    p->id = row.id;
    p->index = i - 1;
    p->condition = row.condition;
    if (participants_.count(p->id)) {
      throw InvalidData(
          fmt::format("{}:{}: participant '{}' twice", assignment.string(), i + 1, p->id));
    }
    recover_log(*p, RoundKind::practice);
    recover_log(*p, RoundKind::main);
    participants_[p->id] = p;
  }
  check_no_stray_logs(dir_ / "logs", participants_, assignment);
  std::string qh = "participant,condition";
  for (const auto& i : settings_.items) qh += "," + i;
  read_done(dir_ / "questionnaire.csv", qh + "\n", participants_, &Participant::questionnaire_done);
  if (!settings_.yes_no_item.empty()) {
    read_done(dir_ / "questionnaire_yesno.csv",
              "participant,condition," + settings_.yes_no_item + "\n", participants_,
              &Participant::yes_no_done);
  }
  read_rounds_shown(dir_ / "collect" / "events.csv", participants_);
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


Stage Study::stage(const ParticipantStatus& s) const noexcept {
  if (s.practice_saved < settings_.practice || s.rounds_saved < settings_.iterations) {
    return (s.practice_saved == 0 && s.rounds_saved == 0 && !settings_.consent.empty())
               ? Stage::consent
               : Stage::rounds;
  }
  return s.questionnaire_done ? Stage::done : Stage::questionnaire;
}

Study::CommitStats Study::commit_stats() const {
  return {committer_->groups(), committer_->appends(), committer_->busy_seconds()};
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
