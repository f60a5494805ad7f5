// `feint score` from its options to its summary (see feint/commands/score_command.hpp).
#include "feint/commands/score_command.hpp"

#include <memory>

#include "feint/io/progress.hpp"
#include "feint/metrics/score.hpp"

namespace feint::commands {

std::string score_command(const ScoreCommandOptions& a) {
  metrics::ScoreSettings s = analysis::score_settings(a.scoring);
  s.rejects_path = a.rejects;
  s.sidecar_path = a.sidecar;
  s.unsorted = a.unsorted;
  s.tool_version = a.tool_version;

  auto progress = std::make_shared<io::ProgressLine>("feint score");
  if (progress->active()) {
    s.on_progress = [progress](const metrics::ScoreProgress& p) {
      progress->update(p.rows_read, p.bytes_read, p.trials_scored, p.trials_rejected);
    };
  }
  const auto summary = metrics::score_to_file(a.inputs, s, a.output);
  progress->finish();
  return metrics::summary_text(summary);
}

}  // namespace feint::commands
