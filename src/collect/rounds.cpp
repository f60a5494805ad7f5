// What participants do: join, ask for a round, submit it, answer the questionnaire
// (feint/collect/study.hpp). Each operation is asynchronous: it validates and formats on the
// caller's thread, hands its appends to the group committer and answers from the committer's
// completion thread once they are synced; nothing here waits for a disk. The synchronous forms
// (tests, in-process callers) wait for the asynchronous ones.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <iterator>

#include "durable.hpp"
#include "feint/collect/study.hpp"
#include "feint/error.hpp"
#include "feint/io/number.hpp"
#include "feint/rng.hpp"
#include "feint/sim/robot_path.hpp"
#include "participant.hpp"

namespace feint::collect {

namespace fs = std::filesystem;
using detail::csv_field;
using detail::GroupCommitter;
using detail::make_status;

namespace {

/// Waits for an asynchronous operation; rethrows its error.
template <class T, class Start>
T wait_for(Start start) {
  auto promise = std::make_shared<std::promise<T>>();
  auto result = promise->get_future();
  start([promise](std::exception_ptr e, T value) {
    if (e) {
      promise->set_exception(e);
    } else {
      promise->set_value(std::move(value));
    }
  });
  return result.get();
}

std::exception_ptr io_error(const std::string& what) {
  return std::make_exception_ptr(IoError(what));
}

}  // namespace

// ---- join: new participants are assigned in batches, one per sync ----------------------------

void Study::join(const std::string& requested, Then<ParticipantStatus> then) {
  std::unique_lock lock(mu_);
  std::string id = requested;
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
    lock.unlock();
    return then(std::make_exception_ptr(Rejection(
                    400, "bad_participant",
                    "participant IDs are 1-64 letters, digits, '_' or '-' (not starting with '-')")),
                {});
  }
  if (const auto it = participants_.find(id); it != participants_.end()) {
    const auto p = it->second;
    lock.unlock();
    ParticipantStatus st;
    {
      std::lock_guard plock(p->mu);
      p->last_seen = detail::unix_now();
      st = make_status(*p, settings_);
    }
    return then(nullptr, std::move(st));
  }
  // Joined already and not yet on disk (a double click): answered with the same row.
  auto same = [&](PendingJoin& j) {
    if (j.id != id) return false;
    j.then.push_back(std::move(then));
    return true;
  };
  if (joins_in_flight_ && std::any_of(joins_in_flight_->begin(), joins_in_flight_->end(), same))
    return;
  if (std::any_of(joins_waiting_.begin(), joins_waiting_.end(), same)) return;
  joins_waiting_.push_back({id, {}, nullptr});
  joins_waiting_.back().then.push_back(std::move(then));
  if (!joins_in_flight_) assign_waiting(lock);
}

void Study::assign_waiting(std::unique_lock<std::mutex>& lock) {
  // One batch at a time: the rows are numbered in order of arrival, and a batch that fails
  // (disk full) leaves no gap in the numbering, as its indices are given again to the next one.
  auto batch = std::make_shared<std::vector<PendingJoin>>(
      std::make_move_iterator(joins_waiting_.begin()), std::make_move_iterator(joins_waiting_.end()));
  joins_waiting_.clear();
  joins_in_flight_ = batch;
  std::size_t index = participants_.size();
  std::string rows, events;
  const std::string now = detail::utc_now();
  for (auto& j : *batch) {
    auto p = std::make_shared<Participant>();
    p->id = j.id;
    p->index = index++;
    const std::size_t c = settings_.conditions.size();
    std::vector<std::size_t> perm(c);
    for (std::size_t i = 0; i < c; ++i) perm[i] = i;
    Rng rng = Rng::stream(settings_.seed, p->index / c);
    sim::shuffle(perm, rng);
    p->condition = perm[p->index % c];
    const std::string& condition = settings_.conditions[p->condition].name;
    rows += fmt::format("{},{},{},{}\n", p->id, p->index, condition, now);
    events += fmt::format("{},{},assigned,{}\n", now, p->id, csv_field(condition));
    j.p = std::move(p);
  }
  lock.unlock();
  // The assignment rows (one write: all or none) and their events in one commit; a participant
  // exists (in memory too) only once its row is on disk.
  std::vector<GroupCommitter::Append> commit;
  commit.push_back({dir_ / "collect" / "assignment.csv", std::string(detail::kAssignmentHeader),
                    std::move(rows)});
  commit.push_back(
      {dir_ / "collect" / "events.csv", std::string(detail::kEventsHeader), std::move(events)});
  committer_->commit_async(std::move(commit), [this, batch](std::vector<GroupCommitter::Result> r) {
    const bool assigned = r[0].error.empty();
    std::unique_lock lock(mu_);
    if (assigned)
      for (auto& j : *batch) participants_[j.id] = j.p;
    joins_in_flight_.reset();
    // The callbacks are taken under the lock: a double click adds to them until here.
    std::vector<std::pair<std::shared_ptr<Participant>, std::vector<Then<ParticipantStatus>>>>
        answers;
    for (auto& j : *batch) answers.emplace_back(j.p, std::move(j.then));
    if (!joins_waiting_.empty()) {
      assign_waiting(lock);  // unlocks
    } else {
      lock.unlock();
    }
    for (auto& [p, thens] : answers) {
      ParticipantStatus st;
      if (assigned) {
        std::lock_guard plock(p->mu);
        p->last_seen = detail::unix_now();
        st = make_status(*p, settings_);
      }
      const auto error = !assigned           ? io_error(r[0].error)
                         : !r[1].error.empty() ? io_error(r[1].error)
                                               : nullptr;
      for (auto& t : thens) t(error, st);
    }
  });
}

// ---- rounds ------------------------------------------------------------------------------

void Study::start_round(const std::string& id, Then<Round> then) {
  std::shared_ptr<Participant> p;
  try {
    p = find(id);
  } catch (...) {
    return then(std::current_exception(), {});
  }
  exclusive(p, [this, p, id, then = std::move(then)]() mutable {
    Round r;
    std::string name;
    bool interrupted = false;
    try {
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
      r = plan_for(*p, kind, iteration);
      name = fmt::format("{} {}", to_string(kind), iteration);
      if (p->shown && p->shown->first == kind && p->shown->second == iteration) {
        ++p->interruptions;
        interrupted = true;
      }
      p->shown = std::make_pair(kind, iteration);
    } catch (...) {
      const auto e = std::current_exception();
      then(e, {});
      return release(p);
    }
    if (!interrupted) {
      note_event(id, "round_shown", name);  // acknowledges nothing: not waited for
      then(nullptr, std::move(r));
      return release(p);
    }
    // The interruption is recorded durably before the round is shown again.
    std::vector<GroupCommitter::Append> commit;
    const fs::path events = dir_ / "collect" / "events.csv";
    commit.push_back(
        {events, std::string(detail::kEventsHeader),
         event_line(id, "interrupted",
                    name + " was shown before and not saved; shown again from its start")});
    commit.push_back(
        {events, std::string(detail::kEventsHeader), event_line(id, "round_shown", name)});
    committer_->commit_async(std::move(commit), [this, p, r = std::move(r), then](auto res) mutable {
      then(res[0].error.empty() ? nullptr : io_error(res[0].error), std::move(r));
      release(p);
    });
  });
}

namespace {

// Order: practice rounds first, then the analysed ones, each 1, 2, ... (called with p.mu held).
template <class P>
void check_round_order(const P& p, RoundKind kind, int iteration, const Settings& settings,
                       const std::string& name) {
  const int k = static_cast<int>(kind);
  const bool practice_open = p.saved[0] < settings.practice;
  const int limit = kind == RoundKind::practice ? settings.practice : settings.iterations;
  if (iteration < 1 || iteration > limit) {
    throw Rejection(409, "out_of_order", fmt::format("{} does not exist in this study", name));
  }
  if (iteration <= p.saved[k]) {
    throw Rejection(409, "duplicate", fmt::format("{} is already saved", name));
  }
  if (iteration != p.saved[k] + 1 || (kind == RoundKind::main && practice_open)) {
    throw Rejection(409, "out_of_order",
                    fmt::format("{} submitted before the rounds before it were saved", name));
  }
}

// Validation: the trace as the page must have recorded it.
void validate_trace(const std::vector<PadSample>& s, const Round& r, const Settings& settings,
                    const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Rejection(422, "invalid_trace", name + ": " + why);
  };
  if (s.size() < 2) throw bad("fewer than 2 samples");
  if (s.size() > settings.max_samples) {
    throw Rejection(
        413, "too_many_samples",
        fmt::format("{}: {} samples (at most {})", name, s.size(), settings.max_samples));
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
    if (dp > settings.pad_speed * dt * (1 + kSpeedTolerance)) {
      throw bad(fmt::format("sample {}: the pad moved {} in {} s, faster than the pad speed {}/s",
                            i + 1, io::format_double(dp), io::format_double(dt),
                            io::format_double(settings.pad_speed)));
    }
  }
  if (s.back().t != r.duration()) {
    throw bad(fmt::format("the last sample must be at the end of the round, t = {}",
                          io::format_double(r.duration())));
  }
}

// The round's log rows: one block of whole lines, so that it is one write, synced before the
// page hears of it. A legacy log keeps its layout (no robot position).
std::string round_rows(const std::string& id, const std::string& condition, int iteration,
                       const Round& r, const Settings& settings, const std::vector<PadSample>& s,
                       bool legacy) {
  const std::string key =
      fmt::format("{},{},{},{},{},{},", id, condition, iteration, sim::to_string(r.strategy),
                  sim::to_string(r.variant), sim::to_string(r.target));
  const std::string speed = io::format_double(settings.pad_speed);
  std::vector<double> times;
  times.reserve(s.size());
  for (const auto& x : s) times.push_back(x.t);
  const auto robot =
      sim::robot_positions(r.strategy, r.variant, r.target, settings.geometry, times);
  std::string block;
  block.reserve(s.size() * (key.size() + 64));
  for (std::size_t i = 0; i < s.size(); ++i) {
    block += key;
    detail::append_double(block, s[i].t);
    block += ',';
    detail::append_double(block, s[i].pad);
    block += ',';
    block += speed;
    if (!legacy) {
      block += ',';
      detail::append_metres(block, robot[i].x);
      block += ',';
      detail::append_metres(block, robot[i].y);
    }
    block += '\n';
  }
  return block;
}

// A pointer study's trace: the belief point held on the map, t from the first touch.
void validate_pointer_trace(const std::vector<PointerSample>& s, const Round& r,
                            const Settings& settings, const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Rejection(422, "invalid_trace", name + ": " + why);
  };
  if (s.size() < 2) throw bad("fewer than 2 samples");
  if (s.size() > settings.max_samples) {
    throw Rejection(
        413, "too_many_samples",
        fmt::format("{}: {} samples (at most {})", name, s.size(), settings.max_samples));
  }
  if (s.front().t != 0) throw bad("the first sample must be at t = 0 (the first touch)");
  const MapBounds b = map_bounds(settings);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i].t) || !std::isfinite(s[i].x) || !std::isfinite(s[i].y))
      throw bad(fmt::format("sample {} is not a number", i + 1));
    if (s[i].x < b.x_min || s[i].x > b.x_max || s[i].y < b.y_min || s[i].y > b.y_max) {
      throw bad(fmt::format("sample {}: ({}, {}) is outside the map [{}, {}] x [{}, {}] m", i + 1,
                            io::format_double(s[i].x), io::format_double(s[i].y),
                            io::format_double(b.x_min), io::format_double(b.x_max),
                            io::format_double(b.y_min), io::format_double(b.y_max)));
    }
    if (i > 0 && !(s[i].t > s[i - 1].t))
      throw bad(fmt::format("sample {}: times must increase", i + 1));
  }
  if (s.back().t != r.duration()) {
    throw bad(fmt::format("the last sample must be at the end of the round, t = {}",
                          io::format_double(r.duration())));
  }
}

// A pointer study's rows: the trial's layout repeated on every row (constant within a trial), the
// robot's exact position on its polyline at each sample.
std::string pointer_rows(const std::string& id, const std::string& condition, int iteration,
                         const Round& r, double speed, const std::vector<PointerSample>& s) {
  std::string key =
      fmt::format("{},{},{},{},{},{},", id, condition, iteration, sim::to_string(r.strategy),
                  sim::to_string(r.variant), r.target_index);
  std::string layout;
  auto point = [&layout](double x, double y) {
    layout += ',';
    detail::append_metres(layout, x);
    layout += ',';
    detail::append_metres(layout, y);
  };
  point(r.layout.start.x, r.layout.start.y);
  for (const auto& q : r.layout.targets) point(q.x, q.y);
  std::string block;
  block.reserve(s.size() * (key.size() + layout.size() + 64));
  for (const auto& x : s) {
    block += key;
    detail::append_double(block, x.t);
    block += ',';
    detail::append_double(block, x.x);
    block += ',';
    detail::append_double(block, x.y);
    block += layout;
    const sim::Point robot = sim::position_on_path(r.waypoints, speed, x.t);
    block += ',';
    detail::append_metres(block, robot.x);
    block += ',';
    detail::append_metres(block, robot.y);
    block += '\n';
  }
  return block;
}

// Once the commit is done: the round counts as saved only when its rows were written; sets the
// participant's new status in `st` and returns the error to answer with.
template <class P, class Done>
std::exception_ptr record_saved_round(P& p, int k, int iteration, const Done& done,
                                      const Settings& settings, ParticipantStatus& st) {
  std::lock_guard lock(p.mu);
  if (!done[0].error.empty()) return io_error(done[0].error);
  p.log_size[k] = done[0].size;
  p.saved[k] = iteration;
  p.shown.reset();
  st = make_status(p, settings);
  // Saved; when its event failed the page hears 503, retries and gets "duplicate".
  return done[1].error.empty() ? nullptr : io_error(done[1].error);
}

}  // namespace

void Study::submit_round(const std::string& id, RoundKind kind, int iteration,
                         std::vector<PadSample> samples, Then<ParticipantStatus> then) {
  if (settings_.belief != BeliefInput::pad) {
    return then(std::make_exception_ptr(Rejection(
                    400, "malformed", "this study takes pointer samples (lines 't,x,y')")),
                {});
  }
  const std::size_t n = samples.size();
  auto rows = [this, id, kind, iteration, s = std::move(samples)](
                  const Round& r, const std::string& condition, bool legacy) {
    const std::string name = fmt::format("{} round {}", to_string(kind), iteration);
    validate_trace(s, r, settings_, name);
    return round_rows(id, condition, iteration, r, settings_, s, legacy);
  };
  submit_rows(id, kind, iteration, n, std::move(rows), std::move(then));
}

void Study::submit_round(const std::string& id, RoundKind kind, int iteration,
                         std::vector<PointerSample> samples, Then<ParticipantStatus> then) {
  if (settings_.belief != BeliefInput::pointer) {
    return then(std::make_exception_ptr(
                    Rejection(400, "malformed", "this study takes pad samples (lines 't,pad')")),
                {});
  }
  const std::size_t n = samples.size();
  auto rows = [this, id, kind, iteration, s = std::move(samples)](
                  const Round& r, const std::string& condition, bool) {
    const std::string name = fmt::format("{} round {}", to_string(kind), iteration);
    validate_pointer_trace(s, r, settings_, name);
    return pointer_rows(id, condition, iteration, r, settings_.geometry.speed, s);
  };
  submit_rows(id, kind, iteration, n, std::move(rows), std::move(then));
}

void Study::submit_rows(const std::string& id, RoundKind kind, int iteration, std::size_t samples,
                        RowsOf rows,
                        Then<ParticipantStatus> then) {
  std::shared_ptr<Participant> p;
  try {
    p = find(id);
  } catch (...) {
    return then(std::current_exception(), {});
  }
  exclusive(p, [this, p, id, kind, iteration, samples, rows = std::move(rows),
                then = std::move(then)]() mutable {
    const int k = static_cast<int>(kind);
    const std::string name = fmt::format("{} round {}", to_string(kind), iteration);
    std::vector<GroupCommitter::Append> commit;
    const fs::path path = log_path(id, kind);
    try {
      Round r;
      bool legacy = false;
      {
        std::lock_guard lock(p->mu);
        p->last_seen = detail::unix_now();
        check_round_order(*p, kind, iteration, settings_, name);
        if (detail::file_size_or_zero(path) != p->log_size[k]) {
          recover_log(*p, kind);  // an earlier failed write left a tail: set it aside first
          if (iteration != p->saved[k] + 1)
            throw Rejection(409, "out_of_order", name + ": state changed");
        }
        r = plan_for(*p, kind, iteration);
        legacy = p->legacy_log[k];
      }
      // The round and its `saved` event in one commit: synced together with whatever other
      // rounds arrived meanwhile (group commit); the event is written only when the round was.
      commit.push_back(
          {path, legacy ? std::string(detail::kLegacyLogHeader) : log_header(settings_),
           rows(r, settings_.conditions[p->condition].name, legacy)});
      commit.push_back(
          {dir_ / "collect" / "events.csv", std::string(detail::kEventsHeader),
           fmt::format("{},{},saved,{}\n", detail::utc_now(), id,
                       csv_field(fmt::format("{} ({} samples)", name, samples)))});
    } catch (...) {
      const auto e = std::current_exception();
      then(e, {});
      return release(p);
    }
    committer_->commit_async(std::move(commit), [this, p, k, iteration, then](auto done) {
      ParticipantStatus st;
      const std::exception_ptr error = record_saved_round(*p, k, iteration, done, settings_, st);
      then(error, std::move(st));
      release(p);
    });
  });
}

// ---- the questionnaire -------------------------------------------------------------------

void Study::submit_questionnaire(const std::string& id, std::map<std::string, std::string> answers,
                                 Then<ParticipantStatus> then) {
  std::shared_ptr<Participant> p;
  try {
    p = find(id);
  } catch (...) {
    return then(std::current_exception(), {});
  }
  exclusive(p, [this, p, id, answers = std::move(answers), then = std::move(then)]() mutable {
    std::vector<GroupCommitter::Append> commit;
    bool with_yes_no = false;
    try {
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
          throw Rejection(422, "invalid_answer",
                          fmt::format("'{}' is not a questionnaire item", k));
        }
      }
      // The yes/no row (once), the Likert row and the event, in one commit, in this order.
      if (!yes_no.empty() && !p->yes_no_done) {
        with_yes_no = true;
        commit.push_back({dir_ / "questionnaire_yesno.csv",
                          "participant,condition," + settings_.yes_no_item + "\n",
                          std::move(yes_no)});
      }
      std::string header = "participant,condition";
      for (const auto& i : settings_.items) header += "," + i;
      commit.push_back({dir_ / "questionnaire.csv", header + "\n", std::move(row)});
      commit.push_back({dir_ / "collect" / "events.csv", std::string(detail::kEventsHeader),
                        event_line(id, "questionnaire", "saved")});
    } catch (...) {
      const auto e = std::current_exception();
      then(e, {});
      return release(p);
    }
    committer_->commit_async(std::move(commit), [this, p, with_yes_no, then](auto done) {
      ParticipantStatus st;
      std::exception_ptr error;
      {
        std::lock_guard lock(p->mu);
        const std::size_t q = with_yes_no ? 1 : 0;
        if (with_yes_no && done[0].error.empty()) p->yes_no_done = true;
        for (std::size_t i = 0; i < done.size() && !error; ++i)
          if (!done[i].error.empty()) error = io_error(done[i].error);
        if (done[q].error.empty()) p->questionnaire_done = true;
        st = make_status(*p, settings_);
      }
      then(error, std::move(st));
      release(p);
    });
  });
}

// ---- the synchronous forms ---------------------------------------------------------------

ParticipantStatus Study::join(const std::string& id) {
  return wait_for<ParticipantStatus>([&](auto then) { join(id, std::move(then)); });
}

Round Study::start_round(const std::string& id) {
  return wait_for<Round>([&](auto then) { start_round(id, std::move(then)); });
}

ParticipantStatus Study::submit_round(const std::string& id, RoundKind kind, int iteration,
                                      const std::vector<PadSample>& samples) {
  return wait_for<ParticipantStatus>(
      [&](auto then) { submit_round(id, kind, iteration, samples, std::move(then)); });
}

ParticipantStatus Study::submit_round(const std::string& id, RoundKind kind, int iteration,
                                      const std::vector<PointerSample>& samples) {
  return wait_for<ParticipantStatus>(
      [&](auto then) { submit_round(id, kind, iteration, samples, std::move(then)); });
}

ParticipantStatus Study::submit_questionnaire(const std::string& id,
                                              const std::map<std::string, std::string>& answers) {
  return wait_for<ParticipantStatus>(
      [&](auto then) { submit_questionnaire(id, answers, std::move(then)); });
}

}  // namespace feint::collect
