#include "feint/metrics/score.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <zlib.h>

#include "feint/error.hpp"
#include "feint/io/file_identity.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"
#include "feint/io/pointer_trace.hpp"
#include "score_detail.hpp"

namespace feint::metrics {

namespace {

namespace fs = std::filesystem;

// An existing path that is not a regular file (/dev/null, a FIFO, a terminal) is written in place
// by AtomicOutput; it gets no sidecar beside it.
bool is_special(const std::string& path) {
  if (path == "-") return false;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  return !ec && fs::exists(st) && !fs::is_regular_file(st);
}

std::string default_sidecar(const std::string& output) {
  return output == "-" || is_special(output) ? std::string() : output + ".meta.json";
}

std::string rejects_for(const ScoreSettings& s, const std::string& output) {
  if (s.on_error != OnError::skip) return {};
  if (!s.rejects_path.empty()) return s.rejects_path;
  return output + ".rejects.csv";
}

void append_row(std::string& buf, const io::Trial& t, const TrialScore& s) {
  auto text = [&](const std::string& v) {
    if (v.find_first_of(",\"\r\n") == std::string::npos) {
      buf += v;
    } else {
      buf += io::csv_escape(v);
    }
    buf.push_back(',');
  };
  auto num = [&](double v) {
    if (!std::isnan(v)) fmt::format_to(std::back_inserter(buf), "{}", v);
    buf.push_back(',');
  };
  text(t.participant);
  text(t.condition);
  fmt::format_to(std::back_inserter(buf), "{},", t.iteration);
  text(t.strategy);
  text(t.variant);
  num(t.target);
  fmt::format_to(std::back_inserter(buf), "{},", s.n_samples);
  num(s.duration);
  num(s.error);
  num(s.confusion);
  num(s.reversal_time);
  fmt::format_to(std::back_inserter(buf), "{},", s.reversals);
  num(s.final_pad);
  if (s.overspeed_segments >= 0) fmt::format_to(std::back_inserter(buf), "{}", s.overspeed_segments);
  buf.push_back(',');
  num(s.signed_area);
  num(s.max_deviation);
  fmt::format_to(std::back_inserter(buf), "{},", s.flips);
  num(s.time_deceived);
  if (!std::isnan(s.final_belief_time)) fmt::format_to(std::back_inserter(buf), "{}", s.final_belief_time);
  if (const auto& p = s.pointer) {
    buf.push_back(',');
    num(p->auc);
    num(p->mad);
    num(p->mad_time);
    fmt::format_to(std::back_inserter(buf), "{},{},", p->xpos_flips, p->ypos_flips);
    num(p->initiation_time);
    if (!std::isnan(p->idle_time)) fmt::format_to(std::back_inserter(buf), "{}", p->idle_time);
  }
  buf.push_back('\n');
}

}  // namespace

std::string to_string(TimeUnit unit) { return unit == TimeUnit::ms ? "ms" : "s"; }

std::optional<TimeUnit> parse_time_unit(std::string_view text) {
  const std::string t = io::to_lower(io::trim(text));
  if (t == "s") return TimeUnit::s;
  if (t == "ms") return TimeUnit::ms;
  return std::nullopt;
}

const std::vector<std::string>& score_columns() {
  static const std::vector<std::string> cols = {
      "participant", "condition", "iteration",     "strategy", "variant",
      "target",      "n_samples", "duration",      "error",    "confusion",
      "reversal_time", "reversals", "final_pad", "overspeed_segments",
      // belief-trace measures, appended so that existing readers keep their columns
      "signed_area", "max_deviation", "flips", "time_deceived", "final_belief_time"};
  return cols;
}

void validate(const ScoreSettings& settings, const std::string& output_path) {
  settings.metrics.validate();
  if (output_path.empty()) throw UsageError("no output given (-o FILE, or -o - for stdout)");
  if (settings.on_error == OnError::strict && !settings.rejects_path.empty()) {
    throw UsageError("--rejects needs --on-error skip (strict mode stops at the first invalid "
                     "trial)");
  }
  if (settings.on_error == OnError::skip && output_path == "-" && settings.rejects_path.empty()) {
    throw UsageError("--on-error skip with -o - needs --rejects FILE (where to list the skipped "
                     "trials)");
  }
  const std::string rejects = rejects_for(settings, output_path);
  if (!rejects.empty() && (rejects == output_path || io::same_file(rejects, output_path))) {
    throw UsageError(fmt::format("--rejects '{}' is the scores file itself", rejects));
  }
}

// The reader's options from the scoring settings (on_reject is set by score_each).
io::TraceOptions reading_options(const ScoreSettings& settings) {
  io::TraceOptions opt = settings.reading;
  opt.on_reject = {};
  opt.column_map = settings.column_map;
  opt.delimiter = settings.delimiter;
  opt.pad_speed = settings.metrics.pad_speed;
  opt.require_pad_speed =
      settings.metrics.norm == ConfusionNorm::speed && !settings.metrics.pad_speed;
  opt.unsorted = settings.unsorted;
  opt.time_divisor = settings.time_unit == TimeUnit::ms ? 1000 : 1;
  return opt;
}

namespace {

// What the time-unit check needs of the scored trials: every duration (8 bytes per trial, for the
// median) and the longest trial, named when the unit is refused.
struct Durations {
  std::vector<double> all;
  double longest = 0;
  std::string longest_at, longest_label;

  void add(const io::Trial& trial, double duration) {
    if (all.empty() || duration > longest) {
      longest = duration;
      longest_at = fmt::format("{}:{}", trial.file, trial.line);
      longest_label = trial.label();
    }
    all.push_back(duration);
  }
};

// A trial the reader accepted but whose score cannot be represented (not finite).
io::Rejection unscorable_rejection(const io::Trial& trial, const InvalidData& e) {
  io::Rejection r;
  r.file = trial.file;
  r.line = trial.line;
  r.participant = trial.participant;
  r.condition = trial.condition;
  r.iteration = std::to_string(trial.iteration);
  r.rows = trial.rows;
  r.reason = e.what();
  return r;
}

// The summary's counts: the reader's, less the trials rejected after reading. Every row read must
// end up either scored or rejected.
template <class Reader>
void count_rows_and_trials(ScoreSummary& summary, const Reader& reader,
                           std::uint64_t trials_scored, std::uint64_t unscorable_trials,
                           std::uint64_t unscorable_rows) {
  summary.files = reader.files_read();
  summary.rows_read = reader.rows_read();
  summary.rows_scored = reader.rows_in_trials() - unscorable_rows;
  summary.rows_rejected = reader.rows_rejected() + unscorable_rows;
  summary.trials_scored = trials_scored;
  summary.trials_rejected = reader.trials_rejected() + unscorable_trials;
  summary.bytes_read = reader.bytes_consumed();
  if (summary.rows_read != summary.rows_scored + summary.rows_rejected) {
    throw std::logic_error(fmt::format("row accounting does not add up: {} read, {} scored, {} "
                                       "rejected", summary.rows_read, summary.rows_scored,
                                       summary.rows_rejected));
  }
}

// Records the median and longest duration, and applies the time-unit plausibility rule: refuses
// seconds that would make the median trial last over 20 minutes, and warns (in
// summary.diagnostics) of a median implausible for the unit given.
void check_time_unit(ScoreSummary& summary, Durations& durations, const ScoreSettings& settings) {
  std::vector<double>& all = durations.all;
  if (all.empty()) return;
  const auto mid = all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2);
  std::nth_element(all.begin(), mid, all.end());
  double median = *mid;
  if (all.size() % 2 == 0) median = 0.5 * (median + *std::max_element(all.begin(), mid));
  summary.median_duration = median;
  summary.max_duration = *std::max_element(all.begin(), all.end());
  const auto t_column = settings.column_map.count("t") != 0 ? settings.column_map.at("t") : "t";
  if (settings.check_durations && settings.time_unit == TimeUnit::s &&
      median > kMedianDurationRefuseS) {
    throw InvalidData(fmt::format(
        "{}: column '{}': the median trial lasts {:.4g} s ({} trials; the longest, trial {}, "
        "{:.4g} s): these times cannot be seconds (a trial lasting more than {:.0f} s = 20 "
        "minutes is not a round of the game); if they are milliseconds, give --time-unit ms",
        durations.longest_at, t_column, median, all.size(), durations.longest_label,
        summary.max_duration, kMedianDurationRefuseS));
  }
  std::string warning, code;
  if (!settings.check_durations) {
    // No plausibility rule asked for.
  } else if (settings.time_unit == TimeUnit::s && median > kMedianDurationHighS) {
    code = "time-unit-ms-suspected";
    warning = fmt::format(
        "the median trial lasts {:.4g} s ({} trials, longest {:.4g} s): implausible for seconds; "
        "if the logs' times are in milliseconds, give --time-unit ms (every confusion and "
        "duration would otherwise be off by a factor of 1000)",
        median, all.size(), summary.max_duration);
  } else if (settings.time_unit == TimeUnit::ms && median < kMedianDurationLowMs) {
    code = "time-unit-s-suspected";
    warning = fmt::format(
        "with --time-unit ms the median trial lasts {:.4g} s ({} trials, longest {:.4g} s): "
        "implausibly short; are the logs' times in seconds already?",
        median, all.size(), summary.max_duration);
  }
  if (!warning.empty()) summary.diagnostics.push_back({code, "", 0, t_column, warning});
}

// Puts the reader's notes first (how the files were read), then the time-unit check's, and hands
// each to on_warning (or standard error).
void report_diagnostics(ScoreSummary& summary, std::vector<io::Diagnostic> notes,
                        const ScoreSettings& settings) {
  notes.insert(notes.end(), summary.diagnostics.begin(), summary.diagnostics.end());
  summary.diagnostics = std::move(notes);
  for (const auto& d : summary.diagnostics) {
    const std::string& warning = d.message;
    summary.warnings.push_back(warning);
    if (settings.on_warning) {
      settings.on_warning(warning);
    } else {
      fmt::print(stderr, "feint: warning: {}\n", warning);
    }
  }
}

// No trial was scored: says why, naming the file(s) when they hold no data rows at all ("the input
// holds no data rows" does not say which file was meant).
[[noreturn]] void throw_nothing_scored(const ScoreSummary& summary,
                                       const std::vector<std::string>& files) {
  if (summary.rows_read == 0) {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < files.size() && i < 3; ++i) {
      names.push_back(files[i] == "-" ? "<stdin>" : files[i]);
    }
    if (files.size() > 3) names.push_back(fmt::format("and {} more", files.size() - 3));
    throw InvalidData(fmt::format("{}: no data rows (a header only; expected one row per pad "
                                  "sample after it), so no valid trial to score",
                                  fmt::join(names, ", ")));
  }
  throw InvalidData(fmt::format("no valid trial: {} rows read, all {} trial(s) rejected",
                                summary.rows_read, summary.trials_rejected));
}

// feint never overwrites its inputs: refuses any output (empty = none) that is one of them.
void refuse_inputs_as_outputs(const std::vector<std::string>& files,
                              std::initializer_list<std::string> outputs) {
  for (const auto& f : files) {
    for (const auto& out : outputs) {
      if (!out.empty() && io::same_file(f, out)) {
        throw UsageError(fmt::format("the output '{}' is also an input: feint never overwrites "
                                     "its inputs", out));
      }
    }
  }
}

// The header; logs of K targets and a pointer add the pointer measures' columns at the end.
void append_header(std::string& buf, bool pointer) {
  auto cols = score_columns();
  if (pointer) cols.insert(cols.end(), detail::pointer_score_columns().begin(), detail::pointer_score_columns().end());
  for (std::size_t i = 0; i < cols.size(); ++i) {
    buf += cols[i];
    buf.push_back(i + 1 < cols.size() ? ',' : '\n');
  }
}

// The range of the trials' pad_speed column (empty when min > max), for the sidecar.
struct SpeedRange {
  double min = std::numeric_limits<double>::infinity(), max = -min;
};

// The sidecar's "settings" object (without its key), as a run with `settings` applied them.
std::string sidecar_settings(const ScoreSettings& settings, const SpeedRange& speeds) {
  const auto& m = settings.metrics;
  std::string j = "{\n";
  j += fmt::format("    \"trim_start\": {},\n    \"trim_end\": {},\n",
                   io::json_number(m.trim_start), io::json_number(m.trim_end));
  j += fmt::format("    \"deadband\": {},\n", io::json_number(m.deadband));
  j += fmt::format("    \"belief_deadband\": {},\n", io::json_number(m.belief_deadband));
  j += fmt::format("    \"confusion_norm\": {},\n", io::json_quote(to_string(m.norm)));
  if (m.pad_speed) {
    j += fmt::format("    \"pad_speed\": {{\"source\": \"option\", \"value\": {}}},\n",
                     io::json_number(*m.pad_speed));
  } else if (speeds.min <= speeds.max) {
    j += fmt::format("    \"pad_speed\": {{\"source\": \"column\", \"min\": {}, \"max\": {}}},\n",
                     io::json_number(speeds.min), io::json_number(speeds.max));
  } else {
    j += "    \"pad_speed\": {\"source\": \"none\"},\n";
  }
  j += fmt::format("    \"overspeed_tolerance\": {},\n", io::json_number(kOverspeedTolerance));
  j += fmt::format("    \"on_error\": \"{}\",\n",
                   settings.on_error == OnError::strict ? "strict" : "skip");
  j += fmt::format("    \"unsorted\": {},\n", settings.unsorted ? "true" : "false");
  j += fmt::format("    \"time_unit\": \"{}\",\n", to_string(settings.time_unit));
  j += fmt::format("    \"delimiter\": {},\n",
                   settings.delimiter == 0 ? std::string("\"auto\"")
                                           : io::json_quote(std::string(1, settings.delimiter)));
  j += "    \"column_map\": {";
  bool first = true;
  for (const auto& [k, v] : settings.column_map) {
    j += fmt::format("{}{}: {}", first ? "" : ", ", io::json_quote(k), io::json_quote(v));
    first = false;
  }
  j += "}\n  }";
  return j;
}

// The sidecar's "units" object (without its key): what each column's numbers measure.
std::string sidecar_units(ConfusionNorm norm) {
  std::string j =
      "{\"duration\": \"s\", \"reversal_time\": \"s since the trial's first sample\", "
      "\"error\": \"pad units, [0, 1]\", \"confusion\": ";
  j += norm == ConfusionNorm::speed ? "\"fraction of full-speed movement, [0, 1]\""
                                    : "\"pad units (paper's eq. 4, unnormalised)\"";
  j += ", \"target\": \"pad coordinate (0 = left, 1 = right)\", "
       "\"signed_area\": \"pad units toward the false side, mean over the window, [-1, 1]\", "
       "\"max_deviation\": \"pad units past 0.5 toward the false target, [-0.5, 0.5]\", "
       "\"flips\": \"count (belief dead band)\", "
       "\"time_deceived\": \"share of the window, [0, 1]\", "
       "\"final_belief_time\": \"s since the trial's first sample; empty if never\"}";
  return j;
}

// The table's size and CRC-32, recorded in the sidecar: a reader can tell whether a sidecar
// describes the table beside it (io::read_scores_provenance ignores one that does not).
struct TableCheck {
  std::uint64_t bytes = 0;
  uLong crc = ::crc32(0L, Z_NULL, 0);
};

// The sidecar: the run's settings, inputs, counts and warnings beside the scores table.
std::string sidecar_json(const ScoreSettings& settings, const std::string& output_path,
                         const std::vector<std::string>& files, const ScoreSummary& summary,
                         const std::string& rejects, const TableCheck& table,
                         const SpeedRange& speeds) {
  std::string j = "{\n";
  j += fmt::format("  \"tool\": \"feint score\",\n  \"feint_version\": {},\n",
                   io::json_quote(settings.tool_version));
  j += fmt::format("  \"output\": {},\n", io::json_quote(output_path));
  j += fmt::format("  \"output_check\": {{\"bytes\": {}, \"crc32\": \"{:08x}\"}},\n", table.bytes,
                   static_cast<unsigned long>(table.crc));
  j += "  \"settings\": " + sidecar_settings(settings, speeds) + ",\n";
  j += "  \"inputs\": [";
  for (std::size_t i = 0; i < files.size(); ++i) {
    j += fmt::format("{}{}", i ? ", " : "", io::json_quote(files[i] == "-" ? "<stdin>" : files[i]));
  }
  j += "],\n";
  j += fmt::format(
      "  \"counts\": {{\"files\": {}, \"rows_read\": {}, \"rows_scored\": {}, "
      "\"rows_rejected\": {}, \"trials_scored\": {}, \"trials_rejected\": {}, "
      "\"overspeed_trials\": {}}},\n",
      summary.files, summary.rows_read, summary.rows_scored, summary.rows_rejected,
      summary.trials_scored, summary.trials_rejected, summary.overspeed_trials);
  j += fmt::format("  \"durations\": {{\"median\": {}, \"max\": {}}},\n",
                   io::json_number(summary.median_duration), io::json_number(summary.max_duration));
  j += "  \"warnings\": [";
  for (std::size_t i = 0; i < summary.warnings.size(); ++i) {
    j += fmt::format("{}{}", i ? ", " : "", io::json_quote(summary.warnings[i]));
  }
  j += "],\n";
  j += fmt::format("  \"rejects\": {},\n",
                   rejects.empty() ? std::string("null") : io::json_quote(rejects));
  j += "  \"units\": " + sidecar_units(settings.metrics.norm) + "\n}\n";
  return j;
}

}  // namespace

namespace {

// Reads every trial with `reader` and scores it with `score` (pad or pointer logs).
template <class Reader>
ScoreSummary score_loop(Reader& reader, const std::vector<std::string>& files, const ScoreSettings& settings,
                        const std::function<void(const io::Trial&, const TrialScore&)>& on_trial,
                        const io::TraceOptions& opt,
                        TrialScore (*score)(const io::Trial&, const MetricSettings&),
                        ScoreProgress& progress) {
  ScoreSummary summary;
  Durations durations;
  io::Trial trial;
  // Trials the reader accepted whose score cannot be represented (not finite): rejected here.
  std::uint64_t unscorable_trials = 0, unscorable_rows = 0;
  while (reader.next(trial)) {
    TrialScore s;
    try {
      s = score(trial, settings.metrics);
    } catch (const InvalidData& e) {
      if (settings.on_error != OnError::skip) throw;
      const io::Rejection r = unscorable_rejection(trial, e);
      ++unscorable_trials;
      unscorable_rows += trial.rows;
      opt.on_reject(r);
      continue;
    }
    if (s.overspeed_segments > 0) ++summary.overspeed_trials;
    durations.add(trial, s.duration);
    on_trial(trial, s);
    ++progress.trials_scored;
    if (settings.on_progress) {
      progress.rows_read = reader.rows_read();
      progress.bytes_read = reader.bytes_consumed();
      settings.on_progress(progress);
    }
  }
  count_rows_and_trials(summary, reader, progress.trials_scored, unscorable_trials,
                        unscorable_rows);
  check_time_unit(summary, durations, settings);
  report_diagnostics(summary, reader.diagnostics(), settings);
  if (summary.trials_scored == 0) throw_nothing_scored(summary, files);
  return summary;
}

}  // namespace

ScoreSummary score_each(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                        const std::function<void(const io::Trial&, const TrialScore&)>& on_trial,
                        const std::function<void(const io::Rejection&)>& on_reject) {
  settings.metrics.validate();
  const auto files = io::expand_inputs(inputs);
  io::TraceOptions opt = reading_options(settings);
  ScoreProgress progress;
  if (settings.on_error == OnError::skip) {
    opt.on_reject = [&](const io::Rejection& r) {
      if (on_reject) on_reject(r);
      ++progress.trials_rejected;
      if (settings.on_progress) settings.on_progress(progress);
    };
  }
  if (!files.empty() && io::is_pointer_log(files.front(), opt)) {
    io::PointerTraceReader reader(files, opt);
    return score_loop(reader, files, settings, on_trial, opt, &detail::score_pointer_trial, progress);
  }
  io::TraceReader reader(files, opt);
  return score_loop(reader, files, settings, on_trial, opt, &score_trial, progress);
}

ScoreSummary score_to_file(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                           const std::string& output_path) {
  validate(settings, output_path);
  const std::string sidecar =
      settings.sidecar_path.empty() ? default_sidecar(output_path) : settings.sidecar_path;
  const std::string rejects = rejects_for(settings, output_path);
  const auto files = io::expand_inputs(inputs);
  refuse_inputs_as_outputs(files, {output_path, sidecar, rejects});

  io::AtomicOutput out(output_path);
  std::string buf;
  buf.reserve(1 << 16);
  append_header(buf, !files.empty() && io::is_pointer_log(files.front(), reading_options(settings)));
  std::ostream& os = out.stream();
  TableCheck table;
  auto emit = [&](const std::string& b) {
    table.crc = ::crc32_z(table.crc, reinterpret_cast<const Bytef*>(b.data()), b.size());
    table.bytes += b.size();
    os.write(b.data(), static_cast<std::streamsize>(b.size()));
  };
  SpeedRange speeds;
  std::string rejects_csv;
  if (!rejects.empty()) rejects_csv = "file,line,participant,condition,iteration,rows,reason\n";
  auto on_reject = [&](const io::Rejection& r) {
    rejects_csv += fmt::format("{},{},{},{},{},{},{}\n", io::csv_escape(r.file), r.line,
                               io::csv_escape(r.participant), io::csv_escape(r.condition),
                               io::csv_escape(r.iteration), r.rows, io::csv_escape(r.reason));
  };
  auto on_trial = [&](const io::Trial& t, const TrialScore& s) {
    append_row(buf, t, s);
    if (t.pad_speed) {
      speeds.min = std::min(speeds.min, *t.pad_speed);
      speeds.max = std::max(speeds.max, *t.pad_speed);
    }
    // Standard output cannot be rolled back: keep the (small) table until the run has succeeded.
    if (!out.is_stdout() && !out.in_place() && buf.size() >= (1 << 16) - 512) {
      emit(buf);
      buf.clear();
    }
  };

  ScoreSummary summary;
  try {
    summary = score_each(files, settings, on_trial, on_reject);
  } catch (const InvalidData&) {
    // Zero valid trials in skip mode: the rejects list is the explanation, so it is still written.
    if (!rejects.empty() && settings.on_error == OnError::skip && !rejects_csv.empty()) {
      io::write_file_atomically(rejects, rejects_csv);
    }
    throw;
  }
  emit(buf);
  summary.output_path = output_path;
  summary.rejects_path = rejects;
  summary.sidecar_path = sidecar;

  std::unique_ptr<io::AtomicOutput> sidecar_out;
  if (!sidecar.empty()) {
    const std::string json =
        sidecar_json(settings, output_path, files, summary, rejects, table, speeds);
    sidecar_out = std::make_unique<io::AtomicOutput>(sidecar);
    sidecar_out->stream() << json;
  }
  std::unique_ptr<io::AtomicOutput> rejects_out;
  if (!rejects.empty()) {
    rejects_out = std::make_unique<io::AtomicOutput>(rejects);
    rejects_out->stream() << rejects_csv;
  }
  // All three are written in full before any is renamed; then they replace the old ones as one
  // unit (under a lock on their folder), the scores last: a scores file never exists without its
  // sidecar, and two runs writing the same output never pair one's scores with the other's sidecar.
  io::commit_together({sidecar_out.get(), rejects_out.get(), &out});
  return summary;
}

std::string summary_text(const ScoreSummary& summary) {
  std::string line = fmt::format("feint score: {} rows read from {} file(s), {} trials scored, {} "
                                 "rejected",
                                 summary.rows_read, summary.files, summary.trials_scored,
                                 summary.trials_rejected);
  if (!summary.rejects_path.empty()) line += fmt::format(" (list in {})", summary.rejects_path);
  line += fmt::format(" -> {}", summary.output_path == "-" ? "stdout" : summary.output_path);
  if (!summary.sidecar_path.empty()) line += fmt::format(" (settings in {})", summary.sidecar_path);
  line += '\n';
  if (summary.overspeed_trials > 0) {
    line += fmt::format("feint score: warning: {} trial(s) move faster than the pad speed (see "
                        "the overspeed_segments column)\n",
                        summary.overspeed_trials);
  }
  return line;
}

}  // namespace feint::metrics
