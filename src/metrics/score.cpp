#include "feint/metrics/score.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/io/output.hpp"

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

bool same_file(const std::string& a, const std::string& b) {
  if (a == "-" || b == "-") return false;
  std::error_code ec1, ec2;
  const auto ca = fs::weakly_canonical(a, ec1), cb = fs::weakly_canonical(b, ec2);
  return !ec1 && !ec2 && ca == cb;
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
  buf.push_back('\n');
}

}  // namespace

const std::vector<std::string>& score_columns() {
  static const std::vector<std::string> cols = {
      "participant", "condition", "iteration",     "strategy", "variant",
      "target",      "n_samples", "duration",      "error",    "confusion",
      "reversal_time", "reversals", "final_pad", "overspeed_segments"};
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
  if (!rejects.empty() && (rejects == output_path || same_file(rejects, output_path))) {
    throw UsageError(fmt::format("--rejects '{}' is the scores file itself", rejects));
  }
}

ScoreSummary score_each(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                        const std::function<void(const io::Trial&, const TrialScore&)>& on_trial,
                        const std::function<void(const io::Rejection&)>& on_reject) {
  settings.metrics.validate();
  const auto files = io::expand_inputs(inputs);
  io::TraceOptions opt;
  opt.column_map = settings.column_map;
  opt.delimiter = settings.delimiter;
  opt.pad_speed = settings.metrics.pad_speed;
  opt.require_pad_speed =
      settings.metrics.norm == ConfusionNorm::speed && !settings.metrics.pad_speed;
  opt.unsorted = settings.unsorted;
  ScoreSummary summary;
  ScoreProgress progress;
  if (settings.on_error == OnError::skip) {
    opt.on_reject = [&](const io::Rejection& r) {
      if (on_reject) on_reject(r);
      ++progress.trials_rejected;
      if (settings.on_progress) settings.on_progress(progress);
    };
  }
  io::TraceReader reader(files, opt);
  io::Trial trial;
  while (reader.next(trial)) {
    const TrialScore s = score_trial(trial, settings.metrics);
    if (s.overspeed_segments > 0) ++summary.overspeed_trials;
    on_trial(trial, s);
    ++progress.trials_scored;
    if (settings.on_progress) {
      progress.rows_read = reader.rows_read();
      progress.bytes_read = reader.bytes_consumed();
      settings.on_progress(progress);
    }
  }
  summary.files = reader.files_read();
  summary.rows_read = reader.rows_read();
  summary.rows_scored = reader.rows_in_trials();
  summary.rows_rejected = reader.rows_rejected();
  summary.trials_scored = progress.trials_scored;
  summary.trials_rejected = reader.trials_rejected();
  summary.bytes_read = reader.bytes_consumed();
  if (summary.rows_read != summary.rows_scored + summary.rows_rejected) {
    throw std::logic_error(fmt::format("row accounting does not add up: {} read, {} scored, {} "
                                       "rejected", summary.rows_read, summary.rows_scored,
                                       summary.rows_rejected));
  }
  if (summary.trials_scored == 0) {
    if (summary.rows_read == 0) {
      throw InvalidData(fmt::format("no valid trial: the input ({} file(s)) holds no data rows",
                                    summary.files));
    }
    throw InvalidData(fmt::format("no valid trial: {} rows read, all {} trial(s) rejected",
                                  summary.rows_read, summary.trials_rejected));
  }
  return summary;
}

ScoreSummary score_to_file(const std::vector<std::string>& inputs, const ScoreSettings& settings,
                           const std::string& output_path) {
  validate(settings, output_path);
  const std::string sidecar =
      settings.sidecar_path.empty() ? default_sidecar(output_path) : settings.sidecar_path;
  const std::string rejects = rejects_for(settings, output_path);
  const auto files = io::expand_inputs(inputs);
  for (const auto& f : files) {
    for (const auto& out : {output_path, sidecar, rejects}) {
      if (!out.empty() && same_file(f, out)) {
        throw UsageError(fmt::format("the output '{}' is also an input: feint never overwrites "
                                     "its inputs", out));
      }
    }
  }

  io::AtomicOutput out(output_path);
  std::string buf;
  buf.reserve(1 << 16);
  {
    const auto& cols = score_columns();
    for (std::size_t i = 0; i < cols.size(); ++i) {
      buf += cols[i];
      buf.push_back(i + 1 < cols.size() ? ',' : '\n');
    }
  }
  std::ostream& os = out.stream();
  double v_min = std::numeric_limits<double>::infinity(), v_max = -v_min;
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
      v_min = std::min(v_min, *t.pad_speed);
      v_max = std::max(v_max, *t.pad_speed);
    }
    // Standard output cannot be rolled back: keep the (small) table until the run has succeeded.
    if (!out.is_stdout() && !out.in_place() && buf.size() >= (1 << 16) - 512) {
      os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
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
  os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  summary.output_path = output_path;
  summary.rejects_path = rejects;
  summary.sidecar_path = sidecar;

  if (!sidecar.empty()) {
    const auto& m = settings.metrics;
    std::string j = "{\n";
    j += fmt::format("  \"tool\": \"feint score\",\n  \"feint_version\": {},\n",
                     io::json_quote(settings.tool_version));
    j += fmt::format("  \"output\": {},\n", io::json_quote(output_path));
    j += "  \"settings\": {\n";
    j += fmt::format("    \"trim_start\": {},\n    \"trim_end\": {},\n", io::json_number(m.trim_start),
                     io::json_number(m.trim_end));
    j += fmt::format("    \"deadband\": {},\n", io::json_number(m.deadband));
    j += fmt::format("    \"confusion_norm\": {},\n", io::json_quote(to_string(m.norm)));
    if (m.pad_speed) {
      j += fmt::format("    \"pad_speed\": {{\"source\": \"option\", \"value\": {}}},\n",
                       io::json_number(*m.pad_speed));
    } else if (v_min <= v_max) {
      j += fmt::format("    \"pad_speed\": {{\"source\": \"column\", \"min\": {}, \"max\": {}}},\n",
                       io::json_number(v_min), io::json_number(v_max));
    } else {
      j += "    \"pad_speed\": {\"source\": \"none\"},\n";
    }
    j += fmt::format("    \"overspeed_tolerance\": {},\n", io::json_number(kOverspeedTolerance));
    j += fmt::format("    \"on_error\": \"{}\",\n",
                     settings.on_error == OnError::strict ? "strict" : "skip");
    j += fmt::format("    \"unsorted\": {},\n", settings.unsorted ? "true" : "false");
    j += fmt::format("    \"delimiter\": {},\n",
                     settings.delimiter == 0 ? std::string("\"auto\"")
                                             : io::json_quote(std::string(1, settings.delimiter)));
    j += "    \"column_map\": {";
    bool first = true;
    for (const auto& [k, v] : settings.column_map) {
      j += fmt::format("{}{}: {}", first ? "" : ", ", io::json_quote(k), io::json_quote(v));
      first = false;
    }
    j += "}\n  },\n";
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
    j += fmt::format("  \"rejects\": {},\n",
                     rejects.empty() ? std::string("null") : io::json_quote(rejects));
    j += "  \"units\": {\"duration\": \"s\", \"reversal_time\": \"s since the trial's first sample\", "
         "\"error\": \"pad units, [0, 1]\", \"confusion\": ";
    j += m.norm == ConfusionNorm::speed ? "\"fraction of full-speed movement, [0, 1]\""
                                        : "\"pad units (paper's eq. 4, unnormalised)\"";
    j += ", \"target\": \"pad coordinate (0 = left, 1 = right)\"}\n}\n";
    // The scores are committed last: a scores file never exists without its sidecar.
    io::write_file_atomically(sidecar, j);
  }
  if (!rejects.empty()) io::write_file_atomically(rejects, rejects_csv);
  out.commit();
  return summary;
}

}  // namespace feint::metrics
