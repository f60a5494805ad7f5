// What the pad's and the pointer's study fits share (observer_study_detail.hpp): the agreement
// table's cells and sums, the notes without their unit.
#include "observer_study_detail.hpp"

#include <cmath>

namespace feint::models::detail::observer {

std::string without_unit(const std::string& note, const std::string& unit) {
  const std::string prefix = unit + ": ";
  return note.rfind(prefix, 0) == 0 ? note.substr(prefix.size()) : note;
}

double PairSums::r() const {
  if (n < 3) return std::nan("");
  const double vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
  if (!(vx > 0) || !(vy > 0)) return std::nan("");
  return (sxy - sx * sy / n) / std::sqrt(vx * vy);
}

double PairSums::rmse() const { return n > 0 ? std::sqrt(sdd / n) : std::nan(""); }
double PairSums::mean_x() const { return n > 0 ? sx / n : std::nan(""); }
double PairSums::mean_y() const { return n > 0 ? sy / n : std::nan(""); }

void AgreementCells::add(const std::string& condition, const std::string& strategy, long long iteration,
                         const TrialAgreement& trial) {
  const std::string cond = condition.empty() ? "all" : condition;
  const std::string strat = strategy.empty() ? "unknown" : strategy;
  // Each trial counts in its own cell and in the "all" margins (once, when it is already "all").
  std::vector<std::string> conds{cond}, strats{strat};
  if (cond != "all") conds.push_back("all");
  if (strat != "all") strats.push_back("all");
  std::vector<long long> its{iteration};
  if (iteration != 0) its.push_back(0);
  for (const auto& c : conds) {
    for (const auto& s : strats) {
      for (long long k : its) {
        auto& g = cells_[{c, s, k}];
        g[0].add(trial.human_error, trial.model_error);
        g[1].add(trial.human_confusion, trial.model_confusion);
        for (std::size_t i = 0; i < trial.model_trace.size(); ++i) g[2].add(trial.human_trace[i], trial.model_trace[i]);
      }
    }
  }
}

std::vector<AgreementRow> AgreementCells::rows() const {
  std::vector<AgreementRow> out;
  for (const auto& [key, g] : cells_) {
    AgreementRow r;
    std::tie(r.condition, r.strategy, r.iteration) = key;
    r.trials = static_cast<std::size_t>(g[0].n);
    r.human_error = g[0].mean_x();
    r.model_error = g[0].mean_y();
    r.error_r = g[0].r();
    r.error_rmse = g[0].rmse();
    r.human_confusion = g[1].mean_x();
    r.model_confusion = g[1].mean_y();
    r.confusion_r = g[1].r();
    r.confusion_rmse = g[1].rmse();
    r.trace_r = g[2].r();
    r.trace_rmse = g[2].rmse();
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace feint::models::detail::observer
