// `feint power observer` results (feint/tables/study_power_render.hpp).
#include "feint/tables/study_power_render.hpp"

#include <fmt/format.h>

namespace feint::tables {

std::string render_study_power(const sim::StudyPowerResult& r, const std::string& source,
                               OutputFormat format, const TablePresentation& presentation) {
  const auto& s = r.settings;
  const auto smallest = r.smallest_n_for_target ? Cell::integer(*r.smallest_n_for_target) : Cell::none();
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    const std::vector<std::string_view> cols = {
        "participants", "power",      "mc_se",      "mean_difference", "studies",   "seed",
        "alpha",        "from_iteration", "iterations", "target_power", "smallest_n"};
    std::vector<Record> recs;
    for (const auto& p : r.points) {
      recs.push_back({Cell::integer(p.participants), Cell::num(p.power), Cell::num(p.mc_se),
                      Cell::num(p.mean_difference), Cell::integer(static_cast<long long>(s.studies)),
                      Cell::str(std::to_string(s.seed)), Cell::num(s.alpha), Cell::integer(s.from_iteration),
                      Cell::integer(s.study.iterations), Cell::num(s.target_power), smallest});
    }
    return format == OutputFormat::csv ? write_csv(cols, recs) : write_json(cols, recs);
  }
  TextTable t;
  t.caption = fmt::format(
      "Simulated power of adaptive > random (mean error, iterations {}\u2013{}), goal-inference "
      "participants, {} studies per size",
      s.from_iteration, s.study.iterations, s.studies);
  t.header = {"Participants per condition", "Power", "MC SE", "Mean difference"};
  t.right_align = {true, true, true, true};
  for (const auto& p : r.points) {
    t.rows.push_back({{std::to_string(p.participants), format_mean(p.power, 3), format_mean(p.mc_se, 4),
                       format_mean(p.mean_difference, 4)},
                      false});
  }
  const auto& o = s.study.observer;
  t.notes.push_back(fmt::format(
      "Each simulated study: every participant's mean trial error over iterations {}\u2013{}, "
      "adaptive (lambda {}) against random by Welch's t, one-sided, alpha {}. Observer{}: {} "
      "participant, beta {} /m, delay {} s, recognition {} log-odds, familiarity half {}, noise sd {}, "
      "pad speed {}/s.",
      s.from_iteration, s.study.iterations, format_mean(s.study.lambda, 2), format_mean(s.alpha, 3),
      source.empty() ? "" : " (" + source + ")", sim::to_string(o.model), format_mean(o.beta, 4),
      format_mean(o.reaction_delay, 3), format_mean(o.recognition_logodds, 3),
      format_mean(o.half_familiarity, 3), format_mean(o.noise_sd, 3), format_mean(o.pad_speed, 3)));
  t.notes.push_back(
      r.smallest_n_for_target
          ? fmt::format("Smallest size with power \u2265 {}: {} participants per condition.",
                        format_mean(s.target_power, 2), *r.smallest_n_for_target)
          : fmt::format("No size given reaches power {}: try larger ones.", format_mean(s.target_power, 2)));
  t.notes.push_back(fmt::format("Monte Carlo SE = sqrt(P (1 \u2212 P) / {}); seed {}.", s.studies, s.seed));
  apply_presentation(t, presentation, "tab:feint-power-observer");
  return render_table(t, format);
}

}  // namespace feint::tables
