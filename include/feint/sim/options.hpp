// feint/sim/options.hpp - the settings of `feint simulate selection | study | trajectories` as the
// command line spells them, and their conversion (with the checks that name the option) into the
// simulators' settings (docs/simulation.md, docs/selection.md, docs/observer.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "feint/models/deceptiveness.hpp"
#include "feint/sim/simulation.hpp"
#include "feint/sim/study.hpp"
#include "feint/sim/trajectory_measures.hpp"

namespace feint::sim {

struct SelectionOptions {
  std::string algorithm = "adaptive";
  double lambda = 0.5;
  int iterations = 20;
  std::uint64_t runs = 10;
  std::uint64_t seed = 1;
  std::uint64_t batch = 10;
  unsigned threads = 0;
  std::string targets = "random";
  bool compare = false;
  std::string sweep;  // FROM:TO:STEP of lambda
  std::string format;
  std::string output = "-";
  std::string sequences;
  std::string occurrence;
};

/// The simulations to run: one, the four algorithms (compare), or a lambda grid (sweep); see
/// selection_grid. Throws UsageError for an unknown algorithm or target order, a bad sweep.
std::vector<SimulationSettings> selection_settings(const SelectionOptions& options);

struct StudyOptions {
  std::string out;
  bool replace = false;  ///< --replace: replace an earlier `feint simulate study` folder whole
  int participants = 20;
  std::string design = "between";  ///< between, or within (each participant in every condition)
  std::string conditions = "adaptive,random";  ///< two or more selection algorithms, comma-separated
  int iterations = 20;
  double lambda = 0.5;
  std::uint64_t seed = 1;
  double sample_rate = 25.0;
  double pad_speed = 0.8;
  std::string participant_model = "goal-inference";
  std::vector<std::string> observer;  // KEY=VALUE
  int targets = 2;                    ///< K >= 2 targets on the map (2 + fixed = the paper's study)
  std::string layout = "fixed";       ///< fixed (a row) or random (drawn per round)
};

/// The study's settings; the heuristic participant model gets feint 0.1's observer with its own
/// defaults, then the pad speed and every NAME=VALUE. Throws UsageError naming a bad value.
StudySettings study_settings(const StudyOptions& options);

struct TrajectoriesOptions {
  double beta = 1.0;
  double tau = 0.0;
  double prior = 0.5;
  double pad_speed = 0.8;
  std::string path;  // a custom path CSV (t,x,y) instead of the paper's strategies
  std::string target = "right";
  std::string format;
  std::string output = "-";
};

/// The measured trajectories and the observer they were measured with.
struct TrajectoryMeasures {
  std::vector<TrajectoryMeasuresRow> rows;
  models::DeceptivenessSettings settings;
};

/// Every strategy of the paper (strategy_measures) in the default geometry, or the path file
/// (read_path_file) toward --target. Throws UsageError for a bad observer or target,
/// InvalidData/IoError naming the path file.
TrajectoryMeasures trajectory_measures(const TrajectoriesOptions& options);

}  // namespace feint::sim
