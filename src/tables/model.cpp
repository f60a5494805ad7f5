// The mixed model table's numbers: scores -> long data -> a mixed model per metric, with its
// contrasts and estimated marginal means (see feint/tables/model.hpp); its renderings are in
// model_render.cpp.
#include "feint/tables/model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"
#include "feint/models/exposure.hpp"

namespace feint::tables {

namespace {

std::string whole_or_double(double v) { return io::format_double(v); }

std::string percent(double conf) { return io::format_double(std::round(conf * 1e6) / 1e4); }

}  // namespace

std::vector<std::string> load_strategies(const io::ScoresTable& scores,
                                         const io::ScoresOptions& options,
                                         const std::string& strategy_column) {
  io::CsvReader reader(scores.path);
  const int pc = reader.column(options.participant_column);
  const int ic = reader.column(options.iteration_column);
  const int cc = reader.column(options.condition_column);
  const int sc = reader.column(strategy_column);
  if (sc < 0)
    throw InvalidData(fmt::format("{}: no column '{}': --exposure and --random need the strategy of each trial",
                                  scores.path, strategy_column));
  std::map<std::tuple<std::string, std::string, long long>, std::string> by_key;
  while (reader.next()) {
    if (pc < 0 || ic < 0) break;
    const std::string participant(io::trim(reader.field(static_cast<std::size_t>(pc))));
    const std::string condition =
        cc >= 0 ? std::string(io::trim(reader.field(static_cast<std::size_t>(cc)))) : "";
    const auto iteration = io::parse_double(io::trim(reader.field(static_cast<std::size_t>(ic))));
    const std::string strategy(io::trim(reader.field(static_cast<std::size_t>(sc))));
    if (strategy.empty())
      throw InvalidData(fmt::format("{}:{}: column '{}': empty strategy (trial {}/{}/{})",
                                    scores.path, reader.line(), strategy_column, participant,
                                    condition, iteration ? whole_or_double(*iteration) : "?"));
    if (iteration) by_key[{participant, condition, static_cast<long long>(*iteration)}] = strategy;
  }
  std::vector<std::string> out;
  out.reserve(scores.records.size());
  for (const auto& r : scores.records) {
    const auto it = by_key.find({r.participant, r.condition, r.iteration});
    if (it == by_key.end())
      throw InvalidData(fmt::format("{}:{}: no strategy for trial {}/{}/{}", scores.path, r.line,
                                    r.participant, r.condition, r.iteration));
    out.push_back(it->second);
  }
  return out;
}

namespace {

// The random slope of the condition needs the condition within participants and its own model.
void check_condition_slope(const ModelOptions& o) {
  if (o.random_condition_slope && !o.condition_within)
    throw UsageError(
        "--random-condition-slope needs the condition within participants (each participant "
        "sees several conditions): (1 + condition | participant) is not identified when each "
        "participant has one condition");
  if (o.random_condition_slope && (o.random_slope || o.exposure))
    throw UsageError(
        "--random-condition-slope does not go with --random-slope or --exposure (one random "
        "slope per model)");
}

// Options that cannot be fitted, in the order the user is told about them.
void check_model_options(const io::ScoresTable& scores, const ModelOptions& options,
                         const std::vector<std::string>* strategy) {
  if (options.random_slope && !options.trend)
    throw UsageError("--random-slope needs --trend (a random slope of the linear trend)");
  if (options.exposure && (options.trend || options.random_slope))
    throw UsageError(
        "--exposure fits its own model (strategy * exposure); drop --trend/--random-slope");
  if ((options.exposure || !options.random_strategy.empty()) &&
      (strategy == nullptr || strategy->size() != scores.records.size()))
    throw std::invalid_argument("build_model_analysis: --exposure and --random need one strategy per record");
  check_condition_slope(options);
  if (!(options.alpha > 0 && options.alpha < 1)) throw UsageError("--alpha must be in (0, 1)");
  if (!(options.conf_level > 0 && options.conf_level < 1))
    throw UsageError("--conf-level must be in (0, 1)");
}

// A participant belongs to one condition (the design's between factor).
void check_condition_between(const io::ScoresTable& scores) {
  std::map<std::string, const io::ScoreRecord*> first;
  for (const auto& r : scores.records) {
    auto [it, fresh] = first.emplace(r.participant, &r);
    if (!fresh && it->second->condition != r.condition)
      throw InvalidData(fmt::format(
          "{}:{}: participant {} is in condition '{}' but in '{}' on line {}: the condition is "
          "between participants",
          scores.path, r.line, r.participant, r.condition, it->second->condition,
          it->second->line));
  }
}

// With --exposure: per record, how often its participant had used its strategy before.
std::vector<double> exposure_of(const io::ScoresTable& scores,
                                const std::vector<std::string>& strategy) {
  std::vector<std::string> participants;
  std::vector<double> its;
  for (const auto& r : scores.records) {
    participants.push_back(r.participant);
    its.push_back(static_cast<double>(r.iteration));
  }
  return models::exposure_counts(participants, its, strategy);
}

// What one metric's models are fitted from; the same for every metric.
struct ModelInput {
  const io::ScoresTable& scores;
  const ModelOptions& options;
  const std::vector<std::string>* strategy;  ///< with --exposure
  std::vector<long long> iterations;         ///< of the file
  std::vector<double> exposure;              ///< with --exposure
};

// The trials with a value of metric `mi`: group and time are condition and iteration, or strategy
// and exposure. An iteration without any value is an error (not with exposure: its time is not
// the iteration).
models::LongData metric_data(const ModelInput& in, const std::string& metric, int mi,
                             std::vector<std::string>& row_strategy) {
  const ModelOptions& options = in.options;
  models::LongData d;
  std::set<long long> iterations_with_value;
  for (std::size_t i = 0; i < in.scores.records.size(); ++i) {
    const auto& r = in.scores.records[i];
    const auto& v = r.values[static_cast<std::size_t>(mi)];
    if (!v) continue;
    iterations_with_value.insert(r.iteration);
    d.participant.push_back(r.participant);
    d.group.push_back(options.exposure ? (*in.strategy)[i] : r.condition);
    d.time.push_back(options.exposure ? in.exposure[i] : static_cast<double>(r.iteration));
    d.y.push_back(*v);
    if (in.strategy) row_strategy.push_back((*in.strategy)[i]);
  }
  if (!options.exposure) {
    for (const long long it : in.iterations)
      if (!iterations_with_value.count(it))
        throw InvalidData(fmt::format(
            "{}: metric '{}': iteration {} has no value for any participant (every trial of it "
            "is empty)",
            in.scores.path, metric, it));
  }
  if (d.y.empty())
    throw InvalidData(fmt::format("{}: metric '{}' has no values", in.scores.path, metric));
  return d;
}

// Missing trials: empty values and absent rows (a participant x iteration without a row).
// Participants with missing trials stay in the model with the trials they have.
// With the condition within participants, per participant x condition that participant saw.
void count_missing(MetricModel& mm, const models::LongData& d, std::size_t n_iterations,
                   bool condition_within) {
  std::map<std::string, std::map<std::string, std::size_t>> have;
  for (std::size_t i = 0; i < d.participant.size(); ++i)
    ++have[d.participant[i]][condition_within ? d.group[i] : std::string()];
  mm.trials_missing = 0;
  for (const auto& [p, per_condition] : have) {
    std::size_t missing = 0;
    for (const auto& [c, n] : per_condition)
      if (n < n_iterations) missing += n_iterations - n;
    if (missing > 0) {
      ++mm.participants_with_missing;
      mm.trials_missing += missing;
    }
  }
}

// Fits the model and writes its lme4 formula.
void fit_metric(MetricModel& mm, const models::LongData& d, const std::vector<std::string>& strategy,
                const ModelOptions& options, const std::string& path) {
  models::ModelSpec spec;
  spec.response = mm.metric;
  spec.group = options.exposure ? "strategy" : "condition";
  spec.time = options.exposure ? "exposure" : "iteration";
  spec.time_scale =
      options.exposure || options.trend ? models::TimeScale::linear : models::TimeScale::factor;
  spec.random_slope = options.random_slope;
  spec.random_group_slope = options.random_condition_slope;
  spec.ddf = options.ddf;
  models::CrossedModelSpec crossed{spec, "strategy", {models::RandomIntercept::participant}};
  crossed.random_terms.insert(crossed.random_terms.end(), options.random_strategy.begin(),
                              options.random_strategy.end());
  try {
    const bool between = !options.exposure && !options.condition_within;
    if (options.random_strategy.empty()) {
      mm.fit = models::fit_mixed_model(d, spec, between);
    } else {
      mm.crossed = models::fit_crossed_model(d, strategy, crossed, between);
      mm.fit = mm.crossed->model;
    }
  } catch (const InvalidData& e) {
    throw InvalidData(fmt::format("{}: {}", path, e.what()));  // name the file
  }
  const bool one_group = mm.fit.group_levels.size() < 2;
  const std::string rhs = one_group ? spec.time : fmt::format("{} * {}", spec.group, spec.time);
  // The random part actually fitted (with one condition, (1 + condition | .) is (1 | .)).
  const std::string random = options.random_slope ? "1 + iteration"
                             : options.random_condition_slope && !one_group ? "1 + condition"
                                                                            : "1";
  mm.formula = mm.crossed ? fmt::format("{} ~ {} + {}", mm.metric, rhs, models::random_formula(crossed))
                         : fmt::format("{} ~ {} + ({} | participant)", mm.metric, rhs, random);
}

// Participants per condition (not with exposure: there a participant has several strategies).
void count_participants(MetricModel& mm, const models::LongData& d) {
  std::map<std::string, std::set<std::string>> per;
  for (std::size_t i = 0; i < d.y.size(); ++i) per[d.group[i]].insert(d.participant[i]);
  for (const auto& g : mm.fit.group_levels)
    mm.participants_per_group.emplace_back(g, per[g].size());
}

// The indices of conditions A and B: --compare's, or the first two levels.
std::pair<std::size_t, std::size_t> compared_levels(const models::MixedModelFit& fit,
                                                    const ModelOptions& options,
                                                    const std::string& path) {
  std::size_t ia = 0, ib = 1;
  if (options.compare) {
    auto find = [&](const std::string& name) {
      const auto it = std::find(fit.group_levels.begin(), fit.group_levels.end(), name);
      if (it == fit.group_levels.end())
        throw InvalidData(fmt::format("{}: --compare: no condition '{}' in the data", path, name));
      return static_cast<std::size_t>(it - fit.group_levels.begin());
    };
    ia = find(options.compare->first);
    ib = find(options.compare->second);
    if (ia == ib) throw UsageError("--compare needs two different conditions");
  }
  return {ia, ib};
}

// Contrasts A - B per iteration, or exposure slopes per strategy; none with one condition.
void add_contrasts(MetricModel& mm, const ModelOptions& options, const std::string& path) {
  const auto& fit = mm.fit;
  if (options.exposure) {
    for (std::size_t k = 0; k < fit.group_levels.size(); ++k) {
      ModelContrast c;
      c.level = fit.group_levels[k];
      c.contrast =
          models::contrast(fit, fit.cell_row(k, 1.0) - fit.cell_row(k, 0.0), options.conf_level);
      mm.contrasts.push_back(std::move(c));
    }
  } else if (fit.group_levels.size() >= 2) {
    const auto [ia, ib] = compared_levels(fit, options, path);
    mm.group1 = fit.group_levels[ia];
    mm.group2 = fit.group_levels[ib];
    for (const double t : fit.time_levels) {
      ModelContrast c;
      c.iteration = t;
      c.contrast =
          models::contrast(fit, fit.cell_row(ia, t) - fit.cell_row(ib, t), options.conf_level);
      mm.contrasts.push_back(std::move(c));
    }
  }
}

// --emmeans and --contrasts; with one condition only what does not compare conditions.
void add_emmeans(MetricModel& mm, const ModelOptions& options) {
  if (!options.emmeans && options.contrast_families.empty()) return;
  if (options.exposure || options.trend)
    throw UsageError(
        "--emmeans and --contrasts need iteration as a factor (not --trend or --exposure)");
  const auto& fit = mm.fit;
  const bool one_group = fit.group_levels.size() < 2;
  if (options.emmeans)
    for (const auto term :
         {models::EmmTerm::cells, models::EmmTerm::condition, models::EmmTerm::iteration}) {
      if (term != models::EmmTerm::iteration && one_group) continue;
      mm.emmeans.push_back(
          {models::to_string(term), "", models::estimated_means(fit, term, options.conf_level)});
    }
  for (const auto family : options.contrast_families) {
    const bool is_poly = family == models::EmmFamily::poly_iteration ||
                         family == models::EmmFamily::poly_in_condition;
    const bool by_condition = family == models::EmmFamily::pairwise_condition ||
                              family == models::EmmFamily::condition_at_iteration;
    if (one_group && by_condition) continue;  // one condition: nothing to contrast
    const models::EmmAdjust adj =
        options.adjust ? *options.adjust
                       : (is_poly ? models::EmmAdjust::none : models::EmmAdjust::tukey);
    mm.emm_contrasts.push_back({models::to_string(family), models::to_string(adj),
                                models::emm_contrasts(fit, family, adj, options.conf_level)});
  }
}

// Adjusts the contrasts' p-values over the iterations (strategies), then labels them and writes
// their APA strings, which quote the adjusted p.
void adjust_and_label(MetricModel& mm, const ModelOptions& options) {
  std::vector<std::optional<double>> ps;
  for (const auto& c : mm.contrasts) ps.push_back(c.contrast.test.p_value);
  const auto adj = stats::p_adjust(ps, options.p_adjust);
  for (std::size_t i = 0; i < mm.contrasts.size(); ++i) {
    auto& c = mm.contrasts[i];
    if (options.p_adjust != stats::PAdjustMethod::none) c.contrast.test.p_adjusted = adj[i];
    if (!options.exposure) c.label = two_sample_label(c.contrast.test, options.alpha);
    if (options.exposure && c.contrast.test.computed) {
      const auto& t = c.contrast.test;
      c.apa = fmt::format("b = {:.4f}, {}% CI [{:.4f}, {:.4f}], t({:.1f}) = {:.2f}, {}",
                          *t.estimate, percent(options.conf_level), *t.conf_low, *t.conf_high,
                          *t.df, *t.statistic, apa_p(*t.p_value));
      if (t.p_adjusted) c.apa += ", adjusted " + apa_p(*t.p_adjusted);
    } else {
      c.apa = apa_string(c.contrast.test);
    }
  }
}

MetricModel build_metric_model(const ModelInput& in, const std::string& metric) {
  const int mi = in.scores.metric_index(metric);
  if (mi < 0)
    throw InvalidData(fmt::format("{}: no metric column '{}'", in.scores.path, metric));
  MetricModel mm;
  mm.metric = metric;
  std::vector<std::string> strategy;  // of d's rows, with --exposure or --random
  models::LongData d = metric_data(in, metric, mi, strategy);
  count_missing(mm, d, in.iterations.size(), in.options.condition_within);
  fit_metric(mm, d, strategy, in.options, in.scores.path);
  if (!in.options.exposure) count_participants(mm, d);
  add_contrasts(mm, in.options, in.scores.path);
  add_emmeans(mm, in.options);
  adjust_and_label(mm, in.options);
  mm.data = std::move(d);
  return mm;
}

}  // namespace

ModelAnalysis build_model_analysis(const io::ScoresTable& scores, const ModelOptions& options,
                                   const std::vector<std::string>* strategy) {
  check_model_options(scores, options, strategy);
  if (!options.condition_within) check_condition_between(scores);
  ModelAnalysis a;
  a.options = options;
  a.source = scores.path;
  const ModelInput in{scores, options, strategy, scores.iterations(),
                      options.exposure ? exposure_of(scores, *strategy) : std::vector<double>{}};
  for (const auto& metric : options.metrics) a.models.push_back(build_metric_model(in, metric));
  return a;
}

void validate(const ModelOptions& o) {
  if ((o.emmeans || !o.contrast_families.empty()) && (o.trend || o.exposure))
    throw UsageError("--emmeans and --contrasts need iteration as a factor (drop --trend/--exposure)");
  if (o.exposure && o.compare) throw UsageError("--compare does not apply to --exposure");
  if (o.random_slope && !o.trend)
    throw UsageError("--random-slope needs --trend (a random slope of the linear trend)");
  if (o.exposure && (o.trend || o.random_slope))
    throw UsageError(
        "--exposure fits its own model (strategy * exposure); drop --trend/--random-slope");
  check_condition_slope(o);
  if (!o.random_strategy.empty() && (o.exposure || o.random_slope || o.random_condition_slope))
    throw UsageError("--random strategy adds random intercepts of the strategy; it does not go with --exposure, "
                     "--random-slope or --random-condition-slope");
  if (!o.random_strategy.empty() && o.ddf == models::DdfMethod::kenward_roger)
    throw UsageError("--random strategy: its models have Satterthwaite df only (drop --ddf kenward-roger)");
}

std::vector<models::RandomIntercept> parse_random_terms(const std::vector<std::string>& values) {
  std::vector<models::RandomIntercept> out;
  for (const auto& v : values) {
    const std::string t(io::trim(v));
    const auto term = t == "strategy"               ? models::RandomIntercept::strategy
                      : t == "participant:strategy" ? models::RandomIntercept::participant_strategy
                                                    : throw UsageError(fmt::format(
                                                          "--random '{}': expected strategy ((1 | strategy), crossed "
                                                          "with participant) or participant:strategy (nested)",
                                                          v));
    if (std::find(out.begin(), out.end(), term) != out.end())
      throw UsageError(fmt::format("--random '{}' given twice", t));
    out.push_back(term);
  }
  return out;
}

}  // namespace feint::tables
