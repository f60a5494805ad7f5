// Deceptiveness of the paper's strategies and path rebuilding (feint/sim/trajectory_measures.hpp).
#include "feint/sim/trajectory_measures.hpp"

#include <cctype>
#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace feint::sim {

models::Goals goals_of(const Geometry& g) noexcept {
  models::Goals goals;
  goals.left = {-g.target_distance / 2, g.target_height};
  goals.right = {g.target_distance / 2, g.target_height};
  return goals;
}

std::vector<models::PathSample> to_path(const std::vector<TrajectorySample>& samples) {
  std::vector<models::PathSample> out;
  out.reserve(samples.size());
  for (const auto& s : samples) out.push_back({s.t, s.x, s.y});
  return out;
}

std::vector<TrajectoryMeasuresRow> strategy_measures(const Geometry& g,
                                                     const models::DeceptivenessSettings& settings) {
  validate(g);
  models::DeceptivenessSettings s = settings;
  s.goals = goals_of(g);
  std::vector<TrajectoryMeasuresRow> rows;
  for (auto st : {Strategy::exaggerating, Strategy::switching, Strategy::ambiguous, Strategy::optimal}) {
    for (auto v : {Variant::main, Variant::v2}) {
      if (st == Strategy::optimal && v == Variant::v2) continue;
      for (auto t : {Target::left, Target::right}) {
        const auto path = to_path(trajectory(st, v, t, g));
        rows.push_back({std::string(to_string(st)), std::string(to_string(v)), std::string(to_string(t)),
                        models::deceptiveness(path, t == Target::right ? models::GoalSide::right
                                                                       : models::GoalSide::left,
                                              s)});
      }
    }
  }
  return rows;
}

std::vector<models::PathSample> read_path_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw IoError(fmt::format("{}: cannot open the path file", file));
  std::string line;
  if (!std::getline(in, line)) throw InvalidData(fmt::format("{}:1: the path file is empty", file));
  const auto head = io::split_csv_line(line);
  int ct = -1, cx = -1, cy = -1;
  for (std::size_t i = 0; i < head.size(); ++i) {
    const std::string h = io::to_lower(std::string(io::trim(head[i])));
    if (h == "t") ct = static_cast<int>(i);
    if (h == "x" || h == "robot_x") cx = static_cast<int>(i);
    if (h == "y" || h == "robot_y") cy = static_cast<int>(i);
  }
  if (ct < 0 || cx < 0 || cy < 0) {
    throw InvalidData(fmt::format("{}:1: the header must name the columns t, x and y (got '{}')", file, line));
  }
  std::vector<models::PathSample> out;
  for (std::uint64_t ln = 2; std::getline(in, line); ++ln) {
    if (io::trim(line).empty()) continue;
    const auto cells = io::split_csv_line(line);
    auto get = [&](int c, const char* name) {
      const auto i = static_cast<std::size_t>(c);
      const auto v = i < cells.size() ? io::parse_double(io::trim(cells[i])) : std::nullopt;
      if (!v) {
        throw InvalidData(fmt::format("{}:{}: column '{}': '{}' is not a number", file, ln, name,
                                      i < cells.size() ? cells[i] : std::string()));
      }
      return *v;
    };
    out.push_back({get(ct, "t"), get(cx, "x"), get(cy, "y")});
  }
  return out;
}

}  // namespace feint::sim
