// Rendering of `feint power` (see power_render.hpp).
#include "feint/tables/power_render.hpp"

#include <fmt/format.h>

#include <cmath>

#include "feint/io/number.hpp"

namespace feint::tables {

namespace {

std::string num(std::optional<double> x, int digits = 4) {
  if (!x) return "";
  return format_mean(*x, digits);
}

}  // namespace

std::string solved_for(const models::TTestPowerSpec& given) {
  if (!given.n) return "n";
  if (!given.delta) return "delta";
  return "power";
}

namespace {

// Which noncentral-t computation this is, and what alpha and the sd mean; under the table and in
// the `note` column of the tidy record.
std::string t_test_power_note(const models::TTestPowerResult& r) {
  const auto& s = r.spec;
  const bool two = s.design == models::TTestDesign::two_sample;
  return fmt::format(
      "Noncentral t (Boost.Math), as R's power.t.test(strict = TRUE) and pwr::pwr.t.test{}; "
      "alpha {} shared by {} test(s) (Bonferroni: {} per test).{}",
      two && s.ratio != 1.0 && !s.welch ? " / pwr.t2n.test" : "", io::format_double(s.alpha),
      s.tests, io::format_double(r.alpha_per_test),
      s.welch
          ? " Welch: noncentral t with the Welch-Satterthwaite df of the true variances (as "
            "MESS::power_welch_t_test), an approximation."
          : (s.design == models::TTestDesign::paired ? " Paired: sd is the sd of the differences."
                                                     : ""));
}

// CSV / JSON: one tidy record.
std::string t_test_power_tidy(const models::TTestPowerResult& r, const std::string& solved,
                              const std::string& note, OutputFormat format) {
  const auto& s = r.spec;
  const bool two = s.design == models::TTestDesign::two_sample;
  const std::vector<std::string_view> cols = {"method",      "type",
                                              "alternative", "solved",
                                              "n1",          "n2",
                                              "n1_ceiling",  "n2_ceiling",
                                              "delta",       "sd",
                                              "sd2",         "alpha",
                                              "tests",       "alpha_per_test",
                                              "power",       "power_at_ceiling",
                                              "df",          "ncp",
                                              "note"};
  Record rec = {Cell::str(r.method),
                Cell::str(std::string(models::to_string(s.design))),
                Cell::str(std::string(stats::to_string(s.alternative))),
                Cell::str(solved),
                Cell::num(r.n1),
                two ? Cell::num(r.n2) : Cell::none(),
                Cell::num(r.n1_ceiling),
                Cell::num(r.n2_ceiling),
                Cell::num(s.delta),
                Cell::num(s.sd),
                Cell::num(s.welch ? std::optional<double>(s.sd2.value_or(s.sd)) : std::nullopt),
                Cell::num(s.alpha),
                Cell::integer(s.tests),
                Cell::num(r.alpha_per_test),
                Cell::num(s.power),
                Cell::num(r.power_at_ceiling),
                Cell::num(r.df),
                Cell::num(r.ncp),
                Cell::str(note)};
  const std::vector<Record> recs = {rec};
  return format == OutputFormat::csv ? write_csv(cols, recs) : write_json(cols, recs);
}

// Text / Markdown / LaTeX: one row per quantity, the solved one starred.
TextTable t_test_power_table(const models::TTestPowerResult& r, const std::string& solved) {
  const auto& s = r.spec;
  const bool two = s.design == models::TTestDesign::two_sample;
  TextTable t;
  t.caption = r.method + " (solved for " + solved + ")";
  t.header = {"Quantity", "Value"};
  t.right_align = {false, true};
  auto row = [&](std::string name, std::string value) {
    t.rows.push_back({{std::move(name), std::move(value)}, false});
  };
  const std::string star = " *";
  if (two) {
    row("n1 (group A)" + (solved == "n" ? star : ""), num(r.n1, 2));
    row("n2 (group B)" + (solved == "n" ? star : ""), num(r.n2, 2));
  } else {
    row(std::string(s.design == models::TTestDesign::paired ? "n (pairs)" : "n") +
            (solved == "n" ? star : ""),
        num(r.n1, 2));
  }
  if (r.n1_ceiling) {
    row("whole participants", two ? fmt::format("{} + {}", io::format_double(*r.n1_ceiling),
                                                io::format_double(*r.n2_ceiling))
                                  : io::format_double(*r.n1_ceiling));
    row("power at whole participants", num(r.power_at_ceiling));
  }
  row("delta" + (solved == "delta" ? star : ""), num(s.delta));
  row(s.welch ? "sd (A)" : "sd", io::format_double(s.sd));
  if (s.welch) row("sd (B)", io::format_double(s.sd2.value_or(s.sd)));
  row("alpha (family)", io::format_double(s.alpha));
  row("tests (m)", std::to_string(s.tests));
  row("alpha per test", io::format_double(r.alpha_per_test));
  row("alternative", std::string(stats::to_string(s.alternative)));
  row("power" + (solved == "power" ? star : ""), num(s.power));
  row("df", num(r.df, 2));
  row("noncentrality", num(r.ncp));
  return t;
}

}  // namespace

std::string render_t_test_power(const models::TTestPowerResult& r, const std::string& solved,
                                OutputFormat format, const TablePresentation& presentation) {
  const std::string note = t_test_power_note(r);
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    return t_test_power_tidy(r, solved, note, format);
  }
  TextTable t = t_test_power_table(r, solved);
  t.notes.push_back("* = solved for. " + note);
  apply_presentation(t, presentation, "tab:feint-power");
  return render_table(t, format);
}

std::string render_simulation_power(const models::SimulationPowerResult& r,
                                    const std::string& source, OutputFormat format,
                                    const TablePresentation& presentation) {
  const auto& d = r.design;
  const auto& o = r.options;
  const std::string corr(models::to_string(o.correction));
  const std::string padj(stats::to_string(o.p_adjust));
  struct Line {
    std::string test;
    std::optional<long long> iteration;
    models::SimulatedPower p;
  };
  std::vector<Line> lines = {
      {"condition:iteration (mixed ANOVA, " + corr + ")", std::nullopt, r.interaction},
      {"condition (mixed ANOVA)", std::nullopt, r.condition},
      {"any iteration (Welch t, " + padj + ")", std::nullopt, r.any_iteration}};
  for (std::size_t j = 0; j < r.iteration.size(); ++j) {
    lines.push_back(
        {"iteration (Welch t, " + padj + ")", static_cast<long long>(j + 1), r.iteration[j]});
  }
  if (format == OutputFormat::csv || format == OutputFormat::json) {
    const std::vector<std::string_view> cols = {"test",    "iteration",  "power",   "mc_se",
                                                "studies", "seed",       "n_a",     "n_b",
                                                "alpha",   "correction", "p_adjust"};
    std::vector<Record> recs;
    for (const auto& l : lines) {
      recs.push_back({Cell::str(l.test), l.iteration ? Cell::integer(*l.iteration) : Cell::none(),
                      Cell::num(l.p.power), Cell::num(l.p.mc_se),
                      Cell::integer(static_cast<long long>(o.studies)),
                      Cell::str(std::to_string(o.seed)),
                      Cell::integer(static_cast<long long>(d.n_a)),
                      Cell::integer(static_cast<long long>(d.n_b)), Cell::num(o.alpha),
                      Cell::str(corr), Cell::str(padj)});
    }
    return format == OutputFormat::csv ? write_csv(cols, recs) : write_json(cols, recs);
  }
  TextTable t;
  t.caption = fmt::format(
      "Simulated power, 2 conditions \u00d7 {} iterations, {} + {} participants, {} studies",
      d.means_a.size(), d.n_a, d.n_b, o.studies);
  t.header = {"Test", "Iteration", "Power", "MC SE"};
  t.right_align = {false, true, true, true};
  for (const auto& l : lines) {
    t.rows.push_back({{l.test, l.iteration ? std::to_string(*l.iteration) : "",
                       format_mean(l.p.power, 3), format_mean(l.p.mc_se, 4)},
                      false});
  }
  const double icc = d.sd_participant * d.sd_participant /
                     (d.sd_participant * d.sd_participant + d.sd_residual * d.sd_residual);
  std::string means_a, means_b;
  for (std::size_t j = 0; j < d.means_a.size(); ++j) {
    means_a += (j ? " " : "") + format_mean(d.means_a[j], 3);
    means_b += (j ? " " : "") + format_mean(d.means_b[j], 3);
  }
  t.notes.push_back(fmt::format(
      "Design{}: y = mean(condition, iteration) + participant + residual; participant sd {}, "
      "residual sd {} (intra-class correlation {}); means A: {}; means B: {}.",
      source.empty() ? "" : " from pilot " + source, format_mean(d.sd_participant, 4),
      format_mean(d.sd_residual, 4), format_mean(icc, 3), means_a, means_b));
  t.notes.push_back(fmt::format(
      "Power = share of simulated studies with p < {} (MC SE = sqrt(power (1 - power) / studies)); "
      "each study is analysed as the real one: mixed ANOVA with the {} correction (mean estimated "
      "GG "
      "epsilon {}), Welch t per iteration adjusted by {} over the {} iterations. Seed {}: the same "
      "seed gives the same result on any machine and thread count. Compound symmetry is assumed, "
      "under which the GG-corrected test is conservative.",
      io::format_double(o.alpha), corr, format_mean(r.mean_gg_eps, 3), padj, d.means_a.size(),
      o.seed));
  apply_presentation(t, presentation, "tab:feint-power-simulated");
  return render_table(t, format);
}

}  // namespace feint::tables
