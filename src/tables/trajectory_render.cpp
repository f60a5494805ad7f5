#include "feint/tables/trajectory_render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::tables {

namespace {

struct Column {
  std::string name;
  bool text;  // a string (quoted in JSON) rather than a number
};

const std::vector<Column>& trajectory_columns() {
  static const std::vector<Column> cols = {{"strategy", true},
                                           {"variant", true},
                                           {"target", true},
                                           {"duration", false},
                                           {"path_length", false},
                                           {"cost_overhead", false},
                                           {"legibility", false},
                                           {"time_deceived", false},
                                           {"last_deceptive_point", false},
                                           {"final_belief", false},
                                           {"belief_error", false},
                                           {"belief_confusion", false},
                                           {"belief_overspeed_segments", false},
                                           {"beta", false},
                                           {"tau", false},
                                           {"prior_right", false},
                                           {"pad_speed", false}};
  return cols;
}

std::vector<std::string> trajectory_cells(const sim::TrajectoryMeasuresRow& r,
                                          const models::DeceptivenessSettings& o) {
  const auto& m = r.measures;
  auto d = [](double x) { return io::format_double(x); };
  return {r.strategy,
          r.variant,
          r.target,
          d(m.duration),
          d(m.path_length),
          d(m.cost_overhead),
          d(m.legibility),
          d(m.time_deceived),
          d(m.last_deceptive_point),
          d(m.final_belief),
          d(m.belief_error),
          d(m.belief_confusion),
          std::to_string(m.belief_overspeed_segments),
          d(o.observer.beta),
          d(o.observer.tau),
          d(o.observer.prior_right),
          d(o.pad_speed)};
}

}  // namespace

std::string render_trajectories(const std::vector<sim::TrajectoryMeasuresRow>& rows,
                                const models::DeceptivenessSettings& o, const std::string& format) {
  const auto& cols = trajectory_columns();
  std::string out;
  if (format == "csv") {
    for (std::size_t i = 0; i < cols.size(); ++i) out += (i ? "," : "") + cols[i].name;
    out += '\n';
    for (const auto& r : rows) {
      const auto cells = trajectory_cells(r, o);
      for (std::size_t i = 0; i < cells.size(); ++i)
        out += (i ? "," : "") + io::csv_escape(cells[i]);
      out += '\n';
    }
    return out;
  }
  if (format == "json") {
    out = "[\n";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto cells = trajectory_cells(rows[k], o);
      out += "  {";
      for (std::size_t i = 0; i < cells.size(); ++i) {
        out += (i ? ", " : "") + io::json_quote(cols[i].name) + ": " +
               (cols[i].text ? io::json_quote(cells[i]) : (cells[i].empty() ? "null" : cells[i]));
      }
      out += k + 1 < rows.size() ? "},\n" : "}\n";
    }
    return out + "]\n";
  }
  const bool md = format == "markdown";
  const std::vector<std::string> head = {"strategy", "variant",    "target",   "T (s)",
                                         "overhead", "legibility", "deceived", "LDP",
                                         "error",    "confusion",  "overspeed"};
  std::vector<std::vector<std::string>> body;
  auto f = [](double x) { return std::isnan(x) ? std::string("-") : fmt::format("{:.4f}", x); };
  for (const auto& r : rows) {
    const auto& m = r.measures;
    body.push_back({r.strategy, r.variant, r.target, fmt::format("{:.2f}", m.duration),
                    f(m.cost_overhead), f(m.legibility), f(m.time_deceived),
                    f(m.last_deceptive_point), f(m.belief_error), f(m.belief_confusion),
                    std::to_string(m.belief_overspeed_segments)});
  }
  std::vector<std::size_t> width(head.size());
  for (std::size_t i = 0; i < head.size(); ++i) {
    width[i] = head[i].size();
    for (const auto& b : body) width[i] = std::max(width[i], b[i].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string l = md ? "|" : "";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string cell = i < 3 ? fmt::format("{:<{}}", cells[i], width[i])
                                     : fmt::format("{:>{}}", cells[i], width[i]);
      l += md ? " " + cell + " |" : (i ? "  " : "") + cell;
    }
    return l + "\n";
  };
  out += fmt::format(
      "Observer: beta = {} 1/m, tau = {} s, P(right) = {}; confusion normalised by the pad "
      "speed v = {} pad units/s.\n",
      io::format_double(o.observer.beta), io::format_double(o.observer.tau),
      io::format_double(o.observer.prior_right), io::format_double(o.pad_speed));
  if (md) out += "\n";
  out += line(head);
  if (md) {
    std::string sep = "|";
    for (std::size_t i = 0; i < head.size(); ++i) sep += " " + std::string(width[i], '-') + " |";
    out += sep + "\n";
  }
  for (const auto& b : body) out += line(b);
  if (md) out += "\n";
  out +=
      "overhead: path length / straight line - 1; legibility: Dragan's time-weighted P(true "
      "goal);\n"
      "deceived: share of time the true goal is the less probable one; LDP: last deceptive point\n"
      "(share of the path); error, confusion: the paper's metrics of the delayed belief b(t) as a "
      "pad;\n"
      "overspeed: segments where b(t) moved faster than v (counted as moving at v).\n";
  return out;
}

}  // namespace feint::tables
