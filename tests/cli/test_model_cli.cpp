// `feint model` end to end: R's values through the tidy CSV, the renderings, and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_helpers.hpp"

namespace {

using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

const std::string kGolden = std::string(FEINT_SOURCE_DIR) + "/tests/golden/models/";

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::string cell;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        f.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    f.push_back(cell);
    rows.push_back(f);
  }
  return rows;
}

// golden[case][quantity][name]
std::map<std::string, std::map<std::string, double>> golden(const std::string& c) {
  std::map<std::string, std::map<std::string, double>> g;
  for (const auto& r : parse_csv(feint::test::read_text(kGolden + "lmm_golden.csv")))
    if (r.size() == 4 && r[0] == c) g[r[1]][r[2]] = std::stod(r[3]);
  return g;
}

struct Tidy {
  std::map<std::string, std::size_t> col;
  std::vector<std::vector<std::string>> rows;
  double num(const std::vector<std::string>& r, const std::string& c) const {
    return std::stod(r.at(col.at(c)));
  }
  std::string str(const std::vector<std::string>& r, const std::string& c) const {
    return r.at(col.at(c));
  }
};

Tidy tidy(const std::string& csv) {
  Tidy t;
  auto rows = parse_csv(csv);
  for (std::size_t i = 0; i < rows.at(0).size(); ++i) t.col[rows[0][i]] = i;
  t.rows.assign(rows.begin() + 1, rows.end());
  return t;
}

void expect_rel(double got, double want, const std::string& what, double tol = 2e-7) {
  EXPECT_LE(std::abs(got - want) / std::max(std::abs(want), 1e-12), tol)
      << what << ": got " << got << ", R " << want;
}

TEST(ModelCli, TidyCsvOfThePaperDesignMatchesLmerTestAndEmmeans) {
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_paper20_missing.csv") +
                           " --metric error --format csv --p-adjust holm --apa");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Tidy t = tidy(r.out);
  auto g = golden("paper20_missing");
  int anova = 0, contrasts = 0;
  for (const auto& row : t.rows) {
    EXPECT_EQ(t.str(row, "metric"), "error");
    if (t.str(row, "table") == "anova") {
      ++anova;
      const std::string term = t.str(row, "term");
      expect_rel(t.num(row, "statistic"), g["F"][term], "F " + term);
      expect_rel(t.num(row, "DenDF"), g["DenDF"][term], "DenDF " + term);
      expect_rel(t.num(row, "p.value"), g["p"][term], "p " + term);
      expect_rel(t.num(row, "sumsq"), g["SumSq"][term], "SumSq " + term);
      EXPECT_EQ(t.str(row, "apa").rfind("F(", 0), 0u) << t.str(row, "apa");
    } else if (t.str(row, "table") == "contrast") {
      ++contrasts;
      const std::string it = t.str(row, "iteration");
      EXPECT_EQ(t.str(row, "contrast"), "adaptive - random");
      EXPECT_NEAR(t.num(row, "estimate"), g["c.estimate"][it], 1e-7) << it;
      expect_rel(t.num(row, "std.error"), g["c.SE"][it], "SE " + it);
      expect_rel(t.num(row, "df"), g["c.df"][it], "df " + it);
      expect_rel(t.num(row, "p.value"), g["c.p"][it], "p " + it);
      expect_rel(t.num(row, "p.adjusted"), g["c.p_holm"][it], "holm " + it);
      const double p = t.num(row, "p.adjusted"), est = t.num(row, "estimate");
      // A model contrast has no Bayes factor or TOST: never "≈" (docs/tables.md "Labels").
      EXPECT_EQ(t.str(row, "label"), p < 0.05 ? (est > 0 ? "A>B" : "A<B") : "n.s.");
    } else if (t.str(row, "table") == "ran_pars" && t.str(row, "term") == "var__Observation") {
      expect_rel(t.num(row, "estimate"), g["vcov"]["Residual NA NA"], "residual variance");
    }
  }
  EXPECT_EQ(anova, 3);
  EXPECT_EQ(contrasts, 20);
}

TEST(ModelCli, ExposureSlopesMatchLmerTest) {
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_exposure.csv") +
                           " --metric error --exposure --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Tidy t = tidy(r.out);
  auto g = golden("exposure");
  int slopes = 0;
  for (const auto& row : t.rows) {
    if (t.str(row, "table") != "slope") continue;
    ++slopes;
    const std::string lv = t.str(row, "level");
    EXPECT_NEAR(t.num(row, "estimate"), g["s.estimate"][lv], 1e-8) << lv;
    expect_rel(t.num(row, "df"), g["s.df"][lv], "df " + lv);
    EXPECT_NEAR(t.num(row, "conf.low"), g["s.lower"][lv], 1e-8) << lv;
    EXPECT_NEAR(t.num(row, "conf.high"), g["s.upper"][lv], 1e-8) << lv;
  }
  EXPECT_EQ(slopes, 3);
}

TEST(ModelCli, TextReportShowsAnovaRandomEffectsContrastsAndNote) {
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_unbalanced4_missing.csv") +
                           " --metric error --apa");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* want :
       {"type III ANOVA (Satterthwaite's df)", "condition:iteration", "Random effects of error",
        "adaptive - random per iteration", "fitted by REML",
        "24 participants (10 in adaptive, 14 "
        "in random), 86 trials.",
        "10 participant x iteration trials without a value of error",
        "ICC = ", "condition: F(1, 22) = 0.65, p = .430"})
    EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
}

TEST(ModelCli, MarkdownLatexAndJsonRender) {
  const std::string in = shell_quote(kGolden + "lmm_trend_slope.csv");
  const auto md = run_feint("model " + in + " --metric error --trend --random-slope --format md");
  ASSERT_EQ(md.exit_code, 0) << md.err;
  EXPECT_NE(md.out.find("| Term | Sum Sq | Mean Sq | NumDF | DenDF | F | p |"), std::string::npos);
  EXPECT_NE(md.out.find("no single ICC"), std::string::npos);
  const auto tex = run_feint("model " + in + " --metric error --trend --format latex");
  ASSERT_EQ(tex.exit_code, 0) << tex.err;
  EXPECT_NE(tex.out.find("\\toprule"), std::string::npos);
  EXPECT_NE(tex.out.find("\\label{tab:feint-model-anova-error}"), std::string::npos);
  const auto json = run_feint("model " + in + " --metric error --trend --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(json.out.front(), '[');
  EXPECT_NE(json.out.find("\"table\": \"anova\""), std::string::npos) << json.out.substr(0, 400);
  EXPECT_NE(json.out.find("\"NumDF\": 1"), std::string::npos);
}

std::string scores(const std::string& body) {
  return "participant,condition,iteration,error\n" + body;
}

TEST(ModelCli, ParticipantInTwoConditionsExits65NamingBothLines) {
  TempDir dir;
  const auto p = dir.path() / "s.csv";
  write_text(p, scores("P1,a,1,0.1\nP1,a,2,0.3\nP2,b,1,0.2\nP2,b,2,0.5\nP1,b,3,0.4\n"));
  const auto r = run_feint("model " + shell_quote(p.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("s.csv:6: participant 'P1' has trials in 2 conditions but participant 'P2' (line 4) in "
                       "one only"),
            std::string::npos)
      << r.err;
  const auto b = run_feint("model " + shell_quote(p.string()) + " --metric error --design between");
  EXPECT_EQ(b.exit_code, 65);
  EXPECT_NE(b.err.find("s.csv:6: participant 'P1' has trials in condition 'b' (line 6) and in 'a' (line 2)"),
            std::string::npos)
      << b.err;
}

TEST(ModelCli, IterationMissingForEverybodyExits65) {
  TempDir dir;
  const auto p = dir.path() / "s.csv";
  write_text(p, scores("P1,a,1,0.1\nP1,a,2,\nP1,a,3,0.2\nP2,b,1,0.2\nP2,b,2,\nP2,b,3,0.6\n"
                       "P3,a,1,0.3\nP3,a,2,\nP3,a,3,0.1\n"));
  const auto r = run_feint("model " + shell_quote(p.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("metric 'error': iteration 2 has no value for any participant"),
            std::string::npos)
      << r.err;
}

TEST(ModelCli, MetricWithoutVarianceExits65) {
  TempDir dir;
  const auto p = dir.path() / "s.csv";
  write_text(p, scores("P1,a,1,0.5\nP1,a,2,0.5\nP2,b,1,0.5\nP2,b,2,0.5\nP3,a,1,0.5\nP3,a,2,0.5\n"));
  const auto r = run_feint("model " + shell_quote(p.string()) + " --metric error");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("metric 'error' has no variance (every value is 0.5)"), std::string::npos)
      << r.err;
}

TEST(ModelCli, ImpossibleOptionsExit64) {
  const std::string in = shell_quote(kGolden + "lmm_balanced5.csv");
  EXPECT_EQ(run_feint("model " + in + " --metric error --random-slope").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error --exposure --trend").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error --alternative greater").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error=0.5").exit_code, 64);
}

TEST(ModelCli, ExposureWithoutStrategyColumnExits65) {
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_balanced5.csv") +
                           " --metric error --exposure");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no column 'strategy'"), std::string::npos) << r.err;
}

TEST(ModelCli, CompareChoosesTheDirectionOfTheContrasts) {
  const std::string in = shell_quote(kGolden + "lmm_balanced5.csv");
  const Tidy ab = tidy(run_feint("model " + in + " --metric error --format csv").out);
  const Tidy ba =
      tidy(run_feint("model " + in + " --metric error --format csv --compare random,adaptive").out);
  ASSERT_EQ(ab.rows.size(), ba.rows.size());
  int n = 0;
  for (std::size_t i = 0; i < ab.rows.size(); ++i) {
    if (ab.str(ab.rows[i], "table") != "contrast") continue;
    ++n;
    EXPECT_EQ(ba.str(ba.rows[i], "contrast"), "random - adaptive");
    EXPECT_DOUBLE_EQ(ab.num(ab.rows[i], "estimate"), -ba.num(ba.rows[i], "estimate"));
    EXPECT_DOUBLE_EQ(ab.num(ab.rows[i], "p.value"), ba.num(ba.rows[i], "p.value"));
  }
  EXPECT_EQ(n, 5);
  EXPECT_EQ(run_feint("model " + in + " --metric error --compare adaptive,nope").exit_code, 65);
}

}  // namespace

namespace {

bool have_latex() {
  return std::system(
             "command -v pdflatex >/dev/null 2>&1 && kpsewhich booktabs.sty >/dev/null 2>&1") == 0;
}

}  // namespace

TEST(ModelCli, LatexCompilesAsAFragmentOfAPaperWithoutOverfullLines) {
  if (!have_latex())
    GTEST_SKIP() << "pdflatex with booktabs not installed: LaTeX compile check skipped";
  TempDir dir;
  const auto tex = dir.path() / "model.tex";
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_paper20_missing.csv") +
                           " --metric error --p-adjust holm --apa --format latex -o " +
                           shell_quote(tex.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  write_text(dir.path() / "paper.tex",
             "\\documentclass{article}\n\\usepackage[T1]{fontenc}\n\\usepackage{booktabs}\n"
             "\\usepackage{graphicx}\n\\usepackage{amsmath}\n\\begin{document}\nText.\n"
             "\\input{model.tex}\n\\end{document}\n");
  const std::string cmd =
      "cd " + shell_quote(dir.path().string()) +
      " && pdflatex -interaction=nonstopmode -halt-on-error paper.tex > out.txt 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << feint::test::read_text(dir.path() / "out.txt");
  EXPECT_EQ(feint::test::read_text(dir.path() / "paper.log").find("Overfull \\hbox"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Degenerate designs exit 65 with a message (never a crash), and scale invariance.

std::string fmt_g17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string five_by(int participants, int iterations, const std::string& skip = "") {
  std::string body;
  for (int k = 0; k < participants; ++k)
    for (int j = 1; j <= iterations; ++j) {
      const std::string id = "P" + std::to_string(k);
      const std::string cond = k % 2 == 0 ? "a" : "b";
      if (!skip.empty() && skip == cond + std::to_string(j)) continue;
      body += id + "," + cond + "," + std::to_string(j) + "," +
              std::to_string(0.3 + 0.01 * ((k * 7 + j * 3) % 11) + 0.02 * k) + "\n";
    }
  return scores(body);
}

feint::test::RunResult model_of(const TempDir& dir, const std::string& text,
                                const std::string& options = "") {
  const auto p = dir.path() / "s.csv";
  write_text(p, text);
  return run_feint("model " + shell_quote(p.string()) + " --metric error " + options);
}

TEST(ModelCli, OneIterationExits65InsteadOfCrashing) {
  TempDir dir;
  const auto r = model_of(dir, five_by(8, 1));
  EXPECT_EQ(r.exit_code, 65) << r.err;
  EXPECT_NE(r.err.find("s.csv: metric 'error': 8 trials of 8 participants: every participant has "
                       "a single trial (one iteration, 1)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("`feint table`"), std::string::npos) << r.err;
  EXPECT_EQ(model_of(dir, five_by(8, 1), "--trend").exit_code, 65);
  // One condition, one iteration.
  std::string one;
  for (int k = 0; k < 6; ++k) one += "P" + std::to_string(k) + ",a,1,0." + std::to_string(k + 1) + "\n";
  EXPECT_EQ(model_of(dir, scores(one)).exit_code, 65);
}

TEST(ModelCli, OneParticipantExits65) {
  TempDir dir;
  const auto r = model_of(dir, scores("P1,a,1,0.1\nP1,a,2,0.3\nP1,a,3,0.2\n"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("1 participant (P1): the mixed model needs at least 2 participants"),
            std::string::npos)
      << r.err;
}

TEST(ModelCli, OneParticipantPerConditionExits65) {
  TempDir dir;
  const auto r = model_of(dir, five_by(2, 5), "--trend --random-slope");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("condition is confounded with participant"), std::string::npos) << r.err;
}

TEST(ModelCli, OneConditionFitsTheOneWayModel) {
  TempDir dir;
  std::string body;
  for (int k = 0; k < 6; ++k)
    for (int j = 1; j <= 3; ++j)
      body += "P" + std::to_string(k) + ",a," + std::to_string(j) + "," +
              std::to_string(0.2 + 0.05 * j + 0.01 * ((k * 5 + j) % 7)) + "\n";
  const auto r = model_of(dir, scores(body), "--format csv");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const Tidy t = tidy(r.out);
  int anova_rows = 0;
  for (const auto& row : t.rows)
    if (t.str(row, "table") == "anova") {
      ++anova_rows;
      EXPECT_EQ(t.str(row, "term"), "iteration");
    }
  EXPECT_EQ(anova_rows, 1);
}

TEST(ModelCli, ParticipantWithASingleTrialIsKept) {
  TempDir dir;
  std::string text = five_by(10, 4);
  // P3 keeps only iteration 2.
  std::string kept;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("P3,", 0) != 0 || line.rfind("P3,b,2,", 0) == 0) kept += line + "\n";
  const auto r = model_of(dir, kept);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 participant x iteration trials without a value of error"), std::string::npos)
      << r.out;
}

TEST(ModelCli, EveryParticipantWithASingleTrialExits65) {
  TempDir dir;
  std::string body;
  for (int k = 0; k < 8; ++k)
    body += "P" + std::to_string(k) + "," + (k % 2 ? "b" : "a") + "," + std::to_string(1 + k / 2 % 2) +
            ",0." + std::to_string(k + 1) + "\n";
  const auto r = model_of(dir, scores(body), "--trend");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("8 trials of 8 participants: every participant has a single trial"),
            std::string::npos)
      << r.err;
}

TEST(ModelCli, EmptyConditionIterationCellExits65AndTrendFitsIt) {
  TempDir dir;
  const std::string text = five_by(10, 4, "a3");
  const auto r = model_of(dir, text);
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no observation of condition 'a' at iteration 3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--trend"), std::string::npos) << r.err;
  EXPECT_EQ(model_of(dir, text, "--trend").exit_code, 0);
}

TEST(ModelCli, RandomSlopeWithTwoTrialsPerParticipantExits65) {
  TempDir dir;
  const auto r = model_of(dir, five_by(10, 2), "--trend --random-slope");
  EXPECT_EQ(r.exit_code, 65) << r.out;
  EXPECT_NE(r.err.find("drop --random-slope"), std::string::npos) << r.err;
}

// The demo study, scored, with its metrics multiplied by 1e-9 ... 1e6: F, df and p of every term
// of every model `feint analyze` and `feint model` fit on it (iteration as a factor, --trend,
// --trend --random-slope; error, and confusion as scored by default and by `feint analyze` on the
// demo) unchanged to 1e-8, Sum Sq scaled by c^2 (at 1e-9 feint exited 70 before issue
// #18). Measured: ~1e-11 (exact derivatives and a Newton-polished optimum, docs/mixed-model.md);
// lmerTest's df at 1e-6 are off by a factor of 1000.
TEST(ModelCli, DemoIsScaleInvariantFrom1e9To1e6) {
  TempDir dir;
  // The demo scored as `feint score` does by default and as `feint analyze data/demo` does
  // (data/demo/feint.toml: confusion-norm = "raw").
  auto score = [&](const std::string& name, const std::string& options) {
    const auto scored = dir.path() / name;
    const auto s = run_feint("score " + shell_quote(std::string(FEINT_SOURCE_DIR) + "/data/demo/logs") +
                             " -o " + shell_quote(scored.string()) + options);
    EXPECT_EQ(s.exit_code, 0) << s.err;
    return parse_csv(feint::test::read_text(scored));
  };
  const auto speed = score("demo.csv", ""), raw = score("demo_raw.csv", " --confusion-norm raw");
  ASSERT_FALSE(speed.empty() || raw.empty());
  const std::vector<std::vector<std::string>>* table = &speed;
  auto anova = [&](const std::string& metric, double c, const std::string& options) {
    const auto& rows = *table;
    std::size_t ec = 0;
    while (rows[0][ec] != metric) ++ec;
    std::string text;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (std::size_t i = 0; i < rows[r].size(); ++i) {
        if (i) text += ",";
        text += (r > 0 && i == ec && !rows[r][i].empty())
                    ? fmt_g17(std::stod(rows[r][i]) * c)
                    : rows[r][i];
      }
      text += "\n";
    }
    const auto p = dir.path() / "scaled.csv";
    write_text(p, text);
    const auto m = run_feint("model " + shell_quote(p.string()) + " --metric " + metric +
                             " --format csv " + options);
    EXPECT_EQ(m.exit_code, 0) << "scale " << c << ": " << m.err;
    std::map<std::string, std::vector<double>> out;  // term -> F, DenDF, p, sumsq
    const Tidy t = tidy(m.out);
    for (const auto& row : t.rows)
      if (t.str(row, "table") == "anova")
        out[t.str(row, "term")] = {t.num(row, "statistic"), t.num(row, "DenDF"),
                                   t.num(row, "p.value"), t.num(row, "sumsq")};
    return out;
  };
  const std::vector<std::pair<const std::vector<std::vector<std::string>>*, std::string>> cases{
      {&speed, "error"}, {&speed, "confusion"}, {&raw, "confusion"}};
  for (const auto& [scored, metric] : cases)
    for (const std::string options : {"", "--trend", "--trend --random-slope"}) {
      table = scored;
      const std::string what = metric + (scored == &raw ? " (raw)" : "");
      const auto ref = anova(metric, 1.0, options);
      ASSERT_EQ(ref.size(), 3u) << what << " " << options;
      for (const double c : {1e-9, 1e-6, 1e-3, 1e6}) {
        const auto got = anova(metric, c, options);
        for (const auto& [term, v] : ref) {
          const std::string at = what + " " + term + " at " + std::to_string(c) + " " + options;
          expect_rel(got.at(term)[0], v[0], "F " + at, 1e-8);
          expect_rel(got.at(term)[1], v[1], "DenDF " + at, 1e-8);
          expect_rel(got.at(term)[2], v[2], "p " + at, 1e-8);
          expect_rel(got.at(term)[3], v[3] * c * c, "Sum Sq " + at, 1e-8);
        }
      }
    }
}

// --ddf kenward-roger: the tidy CSV carries lmerTest::anova(m, ddf = "Kenward-Roger") and
// emmeans' Kenward-Roger contrasts (kr_emm_golden.R) for the data set with a single-trial
// participant; --ddf with another value is a usage error.
TEST(ModelCli, KenwardRogerDdfMatchesPbkrtest) {
  std::map<std::string, std::map<std::string, double>> g;
  for (const auto& r : parse_csv(feint::test::read_text(kGolden + "kr_emm_golden.csv")))
    if (r.size() == 5 && r[0] == "single_trial" && r[1] == "Kenward-Roger") g[r[2]][r[3]] = std::stod(r[4]);
  const auto r = run_feint("model " + shell_quote(kGolden + "lmm_single_trial.csv") +
                           " --metric error --ddf kenward-roger --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Tidy t = tidy(r.out);
  int anova = 0, contrasts = 0;
  for (const auto& row : t.rows) {
    if (t.str(row, "table") == "anova") {
      const std::string term = t.str(row, "term");
      expect_rel(t.num(row, "statistic"), g["F"][term], "F " + term, 1e-6);
      expect_rel(t.num(row, "DenDF"), g["DenDF"][term], "DenDF " + term, 1e-6);
      expect_rel(t.num(row, "p.value"), g["p"][term], "p " + term, 1e-6);
      expect_rel(t.num(row, "sumsq"), g["SumSq"][term], "SumSq " + term, 1e-6);
      ++anova;
    } else if (t.str(row, "table") == "contrast") {
      const std::string name = "adaptive - random|" + t.str(row, "iteration");
      expect_rel(t.num(row, "df"), g["cond_by_it.df"][name], "df " + name, 1e-6);
      expect_rel(t.num(row, "std.error"), g["cond_by_it.SE"][name], "SE " + name, 1e-6);
      expect_rel(t.num(row, "p.value"), g["cond_by_it.p"][name], "p " + name, 1e-6);
      ++contrasts;
    }
  }
  EXPECT_EQ(anova, 3);
  EXPECT_EQ(contrasts, 4);
  const auto text = run_feint("model " + shell_quote(kGolden + "lmm_single_trial.csv") +
                              " --metric error --ddf kenward-roger");
  EXPECT_NE(text.out.find("type III ANOVA (Kenward-Roger's df)"), std::string::npos) << text.out;
  EXPECT_EQ(run_feint("model " + shell_quote(kGolden + "lmm_single_trial.csv") +
                      " --metric error --ddf kr")
                .exit_code,
            64);
}

// --emmeans / --contrasts / --adjust: the tidy CSV carries emmeans' numbers (kr_emm_golden.R,
// the data set with a single-trial participant, Kenward-Roger df), every format renders the
// tables, and impossible combinations are usage errors.
TEST(ModelCli, EmmeansAndContrastsMatchEmmeans) {
  std::map<std::string, std::map<std::string, double>> g;
  for (const auto& r : parse_csv(feint::test::read_text(kGolden + "kr_emm_golden.csv")))
    if (r.size() == 5 && r[0] == "single_trial" && r[1] == "Kenward-Roger") g[r[2]][r[3]] = std::stod(r[4]);
  const std::string in = shell_quote(kGolden + "lmm_single_trial.csv");
  const auto r = run_feint("model " + in +
                           " --metric error --ddf kenward-roger --emmeans --contrasts simple "
                           "--contrasts poly --adjust holm --format csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Tidy t = tidy(r.out);
  int means = 0, holm = 0, poly = 0;
  for (const auto& row : t.rows) {
    const std::string table = t.str(row, "table");
    if (table == "emmean" && t.str(row, "term") == "condition:iteration") {
      const std::string name = t.str(row, "level");
      expect_rel(t.num(row, "estimate"), g["cells.emmean"][name], "emmean " + name, 1e-7);
      expect_rel(t.num(row, "std.error"), g["cells.SE"][name], "SE " + name, 1e-6);
      expect_rel(t.num(row, "df"), g["cells.df"][name], "df " + name, 1e-6);
      expect_rel(t.num(row, "conf.low"), g["cells.lower"][name], "lower " + name, 1e-6);
      ++means;
    } else if (table == "emm_contrast" && t.str(row, "term") == "pairwise ~ iteration | condition") {
      const std::string name = t.str(row, "contrast") + "|" + t.str(row, "group");
      EXPECT_EQ(t.str(row, "label"), "holm");
      expect_rel(t.num(row, "p.adjusted"), g["it_by_cond.holm.p"][name], "holm p " + name, 1e-6);
      expect_rel(t.num(row, "conf.high"), g["it_by_cond.holm.upper"][name], "upper " + name, 1e-6);
      ++holm;
    } else if (table == "emm_contrast" && t.str(row, "term") == "poly ~ iteration | condition") {
      // --adjust holm applies to poly too (emmeans' default for poly would be none).
      const std::string name = t.str(row, "contrast") + "|" + t.str(row, "group");
      EXPECT_NEAR(t.num(row, "estimate"), g["poly_by_cond.estimate"][name], 1e-8) << name;
      expect_rel(t.num(row, "p.value"), g["poly_by_cond.p"][name], "poly p " + name, 1e-6);
      ++poly;
    }
  }
  EXPECT_EQ(means, 8);
  EXPECT_EQ(holm, 12);
  EXPECT_EQ(poly, 6);

  for (const std::string f : {"text", "markdown", "latex", "json"}) {
    // Tukey (a studentized-range quantile per contrast) only in one format, to keep the test fast.
    const auto out = run_feint("model " + in + " --metric error --emmeans --contrasts " +
                               (f == "text" ? "pairwise" : "poly") + " --format " + f);
    ASSERT_EQ(out.exit_code, 0) << f << out.err;
    if (f == "json") {
      EXPECT_NE(out.out.find("\"table\": \"emm_contrast\""), std::string::npos);
      EXPECT_NE(out.out.find("\"label\": \"none\""), std::string::npos);
    } else {
      EXPECT_NE(out.out.find("estimated marginal means"), std::string::npos) << f;
      if (f == "text") {
        EXPECT_NE(out.out.find("pairwise ~ iteration (p adjustment: tukey)"), std::string::npos);
      } else {
        EXPECT_NE(out.out.find("(p adjustment: none)"), std::string::npos) << f;
      }
    }
    if (f == "latex") {
      EXPECT_NE(out.out.find("\\label{tab:feint-model-emmeans-error}"), std::string::npos);
      EXPECT_NE(out.out.find("\\label{tab:feint-model-emm-contrasts-error-2}"), std::string::npos);
      EXPECT_NE(out.out.find("\\begin{tabular}"), std::string::npos);
    }
  }
  EXPECT_EQ(run_feint("model " + in + " --metric error --emmeans --trend").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error --contrasts poly --adjust tukey").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error --contrasts all").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric error --adjust holm").exit_code, 64);
}

// --random strategy / participant:strategy (docs/crossed-random-effects.md): the type-III table of
// `feint model` equals lmerTest's anova(m) of the same model (tests/golden/models/
// crossed_anova_golden.R on crossed_data.csv), and the strategy's variance is a random-effects row.
TEST(ModelCli, RandomStrategyInterceptsEqualLmerTest) {
  TempDir dir;
  std::map<std::string, std::string> files;  // data set -> scores file
  std::map<std::string, std::string> text;
  for (const auto& r : parse_csv(feint::test::read_text(kGolden + "crossed_data.csv"))) {
    if (r.size() < 6 || r[0] == "dataset") continue;
    auto& t = text[r[0]];
    if (t.empty()) t = "participant,condition,iteration,strategy,y\n";
    t += r[1] + "," + r[2] + "," + r[3] + "," + r[4] + "," + r[5] + "\n";
  }
  std::size_t checked = 0;
  for (const auto& [ds, body] : text) {
    if (ds == "trend") continue;  // iteration as a number: --trend, checked in tests/models
    const auto path = dir / (ds + ".csv");
    write_text(path, body);
    for (const std::string model : {"crossed", "nested"}) {
      const auto r = run_feint("model " + shell_quote(path.string()) + " --metric y --format csv --random " +
                               (model == "crossed" ? "strategy" : "participant:strategy"));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto rows = parse_csv(r.out);
      std::map<std::string, std::size_t> col;
      for (std::size_t i = 0; i < rows.at(0).size(); ++i) col[rows[0][i]] = i;
      for (const auto& g : parse_csv(feint::test::read_text(kGolden + "crossed_anova_golden.csv"))) {
        if (g.size() < 5 || g[0] != ds || g[1] != model) continue;
        const std::string q = g[3] == "F value" ? "statistic" : g[3] == "Pr(>F)" ? "p.value" : g[3];
        for (const auto& row : rows)
          if (row.size() > col["term"] && row[col["table"]] == "anova" && row[col["term"]] == g[2]) {
            const double want = std::stod(g[4]), got = std::stod(row.at(col.at(q)));
            EXPECT_NEAR(got, want, 1e-6 * std::max(1.0, std::abs(want))) << ds << " " << model << " " << g[2] << " " << q;
            ++checked;
          }
      }
      const std::string group = model == "crossed" ? "strategy" : "participant:strategy";
      EXPECT_NE(r.out.find("ran_pars,var__(Intercept)," + group + ","), std::string::npos) << r.out.substr(0, 600);
    }
  }
  EXPECT_EQ(checked, 5u * 2 * 3 * 4);
}

TEST(ModelCli, RandomStrategyRefusesWhatItCannotFit) {
  TempDir dir;
  const auto path = dir / "s.csv";
  write_text(path, "participant,condition,iteration,y\nP1,a,1,0.1\nP1,a,2,0.3\nP2,b,1,0.2\nP2,b,2,0.5\n");
  const std::string in = shell_quote(path.string());
  auto r = run_feint("model " + in + " --metric y --random strategies");
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--random 'strategies': expected strategy"), std::string::npos) << r.err;
  EXPECT_EQ(run_feint("model " + in + " --metric y --random strategy --exposure").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric y --random strategy --ddf kenward-roger").exit_code, 64);
  EXPECT_EQ(run_feint("model " + in + " --metric y --random strategy --random strategy").exit_code, 64);
  EXPECT_EQ(run_feint("model - --metric y --random strategy", read_text(path)).exit_code, 64);
  r = run_feint("model " + in + " --metric y --random strategy");
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no column 'strategy': --exposure and --random need the strategy"), std::string::npos) << r.err;
}
