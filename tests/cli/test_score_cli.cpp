// End-to-end tests of `feint score` (runs FEINT_EXE): outputs, sidecar, exit codes, messages,
// lenient accounting and atomic outputs.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_helpers.hpp"
#include "feint/io/csv.hpp"
#include "feint/io/number.hpp"

namespace fs = std::filesystem;
using feint::test::read_text;
using feint::test::run_feint;
using feint::test::shell_quote;
using feint::test::TempDir;
using feint::test::write_text;

namespace {

const std::string kHeader = "participant,condition,iteration,strategy,variant,target,t,pad,pad_speed\n";

// Rows of one trial from the samples (t, mu).
std::string trial_rows(const std::string& key, const std::string& target, const std::vector<double>& t,
                       const std::vector<double>& mu, const std::string& speed = "0.25") {
  std::string s;
  for (std::size_t i = 0; i < t.size(); ++i) {
    s += key + ",exaggerating,main," + target + "," + feint::io::format_double(t[i]) + "," +
         feint::io::format_double(mu[i]) + "," + speed + "\n";
  }
  return s;
}

const std::vector<double> kT10 = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
const std::vector<double> kMuB = {0.5, 0.25, 0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1};  // metrics.md B
const std::vector<double> kMuA = {0.5, 0.75, 1, 1, 1, 1, 1, 1, 1, 1, 1};          // metrics.md A

std::string good_log() {
  return kHeader + trial_rows("P01,adaptive,1", "right", kT10, kMuB) +
         trial_rows("P01,adaptive,2", "right", kT10, kMuA) +
         trial_rows("P02,random,1", "1", kT10, kMuB);
}

// Parsed scores CSV: one map column -> value per row.
std::vector<std::map<std::string, std::string>> parse_scores(const std::string& text) {
  std::vector<std::map<std::string, std::string>> rows;
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    const auto f = feint::io::split_csv_line(line);
    if (header.empty()) {
      header = f;
      continue;
    }
    std::map<std::string, std::string> r;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(r);
  }
  return rows;
}

double num(const std::string& s) { return *feint::io::parse_double(s); }

std::string q(const fs::path& p) { return shell_quote(p.string()); }

// Files in a directory (to check that nothing, not even a temporary, is left behind).
std::vector<std::string> listing(const fs::path& d) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(CliHelpers, CapturesExitCodeAndStreams) {
  const auto help = run_feint("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("score"), std::string::npos);
  const auto bad = run_feint("--no-such-option");
  EXPECT_EQ(bad.exit_code, 64);
  EXPECT_FALSE(bad.err.empty());
}

TEST(ScoreCli, HelpExplainsEveryOptionWithUnits) {
  const auto r = run_feint("score --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--output", "--trim", "--trim-start", "--trim-end", "--deadband",
                          "--confusion-norm", "--pad-speed", "--map", "--delimiter", "--on-error",
                          "--rejects", "--unsorted", "--sidecar", "pad units per second",
                          "seconds", "65"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
}

TEST(ScoreCli, ScoresWorkedExamplesAndWritesSidecar) {
  TempDir d;
  write_text(d / "log.csv", good_log());
  // The worked examples' `speed` column (raw, the default, is checked below).
  const auto r = run_feint("score " + q(d / "log.csv") + " --confusion-norm speed -o " + q(d / "scores.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = parse_scores(read_text(d / "scores.csv"));
  ASSERT_EQ(rows.size(), 3U);
  const std::string header = read_text(d / "scores.csv").substr(0, read_text(d / "scores.csv").find('\n'));
  EXPECT_EQ(header, "participant,condition,iteration,strategy,variant,target,n_samples,duration,error,"
                    "confusion,reversal_time,reversals,final_pad,overspeed_segments,signed_area,"
                    "max_deviation,flips,time_deceived,final_belief_time");
  EXPECT_EQ(rows[0].at("participant"), "P01");
  EXPECT_EQ(rows[0].at("condition"), "adaptive");
  EXPECT_EQ(rows[0].at("iteration"), "1");
  EXPECT_EQ(rows[0].at("strategy"), "exaggerating");
  EXPECT_EQ(rows[0].at("target"), "1");
  EXPECT_EQ(rows[0].at("n_samples"), "11");
  // The written numbers round-trip: they reproduce the exact fractions to 1e-12.
  EXPECT_NEAR(num(rows[0].at("error")), 115.0 / 144, 1e-12);
  EXPECT_NEAR(num(rows[0].at("confusion")), 217.0 / 360, 1e-12);
  EXPECT_EQ(rows[0].at("reversal_time"), "6");
  EXPECT_NEAR(num(rows[1].at("error")), 1.0 / 32, 1e-12);
  EXPECT_EQ(rows[1].at("confusion"), "0");
  EXPECT_EQ(rows[1].at("reversal_time"), "");  // never reverses
  EXPECT_EQ(rows[2].at("condition"), "random");
  // The belief-trace measures (docs/metrics.md worked examples B and A, dead band 0.05).
  EXPECT_NEAR(num(rows[0].at("signed_area")), 115.0 / 144, 1e-12);
  EXPECT_EQ(rows[0].at("max_deviation"), "0.5");
  EXPECT_EQ(rows[0].at("flips"), "1");
  EXPECT_NEAR(num(rows[0].at("time_deceived")), 73.0 / 90, 1e-12);
  EXPECT_NEAR(num(rows[0].at("final_belief_time")), 41.0 / 5, 1e-12);
  EXPECT_EQ(rows[1].at("max_deviation"), "-0.125");
  EXPECT_NEAR(num(rows[1].at("final_belief_time")), 0.2, 1e-12);
  // The summary line accounts for the run.
  EXPECT_NE(r.err.find("33 rows read from 1 file(s), 3 trials scored, 0 rejected"), std::string::npos)
      << r.err;
  const auto meta = read_text(d / "scores.csv.meta.json");
  for (const char* s : {"\"trim_start\": 0.05", "\"trim_end\": 0.05", "\"deadband\": 1e-09",
                        "\"belief_deadband\": 0.05",
                        "\"confusion_norm\": \"speed\"", "\"source\": \"column\"", "\"min\": 0.25",
                        "\"feint_version\": ", "\"trials_scored\": 3", "\"rows_read\": 33",
                        "log.csv"}) {
    EXPECT_NE(meta.find(s), std::string::npos) << s << "\n" << meta;
  }
}

TEST(ScoreCli, RawNormalisationTrimAndPadSpeedOptions) {
  TempDir d;
  write_text(d / "log.csv", good_log());
  auto r = run_feint("score " + q(d / "log.csv") + " --confusion-norm raw -o " + q(d / "raw.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = parse_scores(read_text(d / "raw.csv"));
  EXPECT_NEAR(num(rows[0].at("confusion")), 217.0 / 320, 1e-12);
  EXPECT_NE(read_text(d / "raw.csv.meta.json").find("\"confusion_norm\": \"raw\""), std::string::npos);

  // No trimming: |1 - mu| of B integrates to 0.625+0.875+4+0.875+0.625+0.375+0.125 = 7.5 over 10 s.
  r = run_feint("score " + q(d / "log.csv") + " --trim 0 -o " + q(d / "t0.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rows = parse_scores(read_text(d / "t0.csv"));
  EXPECT_NEAR(num(rows[0].at("error")), 0.75, 1e-12);
  EXPECT_NE(read_text(d / "t0.csv.meta.json").find("\"trim_start\": 0,"), std::string::npos);

  // --pad-speed 0.125: the pad (0.25/s) now overspeeds on every moving segment; m clamps to 1.
  r = run_feint("score " + q(d / "log.csv") + " --confusion-norm speed --pad-speed 0.125 -o " + q(d / "v.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rows = parse_scores(read_text(d / "v.csv"));
  EXPECT_NEAR(num(rows[0].at("confusion")), 217.0 / 360, 1e-12);
  EXPECT_EQ(rows[0].at("overspeed_segments"), "6");
  EXPECT_NE(r.err.find("faster than the pad speed"), std::string::npos) << r.err;
  EXPECT_NE(read_text(d / "v.csv.meta.json").find("\"source\": \"option\", \"value\": 0.125"),
            std::string::npos);

  // Separate trims.
  r = run_feint("score " + q(d / "log.csv") + " --trim-start 0 --trim-end 0.5 -o " + q(d / "se.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rows = parse_scores(read_text(d / "se.csv"));
  // B on [0, 5]: |1 - mu| integrates to 0.625+0.875+1+1+1 = 4.5 over 5 s.
  EXPECT_NEAR(num(rows[0].at("error")), 0.9, 1e-12);
}

TEST(ScoreCli, StrictModeStopsAtTheFirstInvalidRowAndLeavesNoOutput) {
  TempDir d;
  std::string log = good_log();
  log += "P07,adaptive,3,exaggerating,main,right,0,0.5,0.25\n";
  log += "P07,adaptive,3,exaggerating,main,right,0.1,1.7,0.25\n";
  write_text(d / "in" / "p07.csv", log);
  fs::create_directories(d / "out");
  const auto r = run_feint("score " + q(d / "in" / "p07.csv") + " -o " + q(d / "out" / "s.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("p07.csv:36: column 'pad': 1.7 is outside [0, 1] (trial P07/adaptive/3)"),
            std::string::npos) << r.err;
  EXPECT_TRUE(listing(d / "out").empty()) << "a failing run left files behind";
}

TEST(ScoreCli, ExitCodesForUsageAndIoErrors) {
  TempDir d;
  write_text(d / "log.csv", good_log());
  const std::string in = q(d / "log.csv");
  const std::string out = " -o " + q(d / "s.csv");
  EXPECT_EQ(run_feint("score " + q(d / "missing.csv") + out).exit_code, 74);
  EXPECT_EQ(run_feint("score " + in + " -o " + q(d / "no-such-dir" / "s.csv")).exit_code, 74);
  EXPECT_EQ(run_feint("score " + in).exit_code, 64);  // -o is required
  EXPECT_EQ(run_feint("score " + in + out + " --trim 1.2").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --trim 0.1 --trim-start 0.1").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --trim-start 0.6 --trim-end 0.5").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --deadband -1").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --belief-deadband 0.5").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --pad-speed 0").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --confusion-norm fancy").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --on-error maybe").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --map bogus=x").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --map pad").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --delimiter x").exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + out + " --rejects " + q(d / "r.csv")).exit_code, 64);
  EXPECT_EQ(run_feint("score " + in + " -o - --on-error skip").exit_code, 64);
  const auto self = run_feint("score " + in + " -o " + in);
  EXPECT_EQ(self.exit_code, 64);
  EXPECT_NE(self.err.find("also an input"), std::string::npos) << self.err;
  EXPECT_EQ(read_text(d / "log.csv"), good_log());
  EXPECT_FALSE(fs::exists(d / "s.csv"));
  // By any other name: a hard link (a different path, the same file) is refused too.
  fs::create_hard_link(d / "log.csv", d / "hard.csv");
  const auto hard = run_feint("score " + in + " -o " + q(d / "hard.csv"));
  EXPECT_EQ(hard.exit_code, 64) << hard.err;
  EXPECT_NE(hard.err.find("also an input"), std::string::npos) << hard.err;
  EXPECT_EQ(read_text(d / "log.csv"), good_log());
}

TEST(ScoreCli, SpeedNormalisationWithoutPadSpeedSaysHowToGiveIt) {
  TempDir d;
  write_text(d / "log.csv", "participant,iteration,target,t,pad\nP1,1,left,0,0.5\nP1,1,left,1,0.4\n");
  auto r = run_feint("score " + q(d / "log.csv") + " --confusion-norm speed -o " + q(d / "s.csv"));
  EXPECT_EQ(r.exit_code, 64);
  EXPECT_NE(r.err.find("--pad-speed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--confusion-norm raw"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "s.csv"));
  r = run_feint("score " + q(d / "log.csv") + " --pad-speed 1 -o " + q(d / "s.csv"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_feint("score " + q(d / "log.csv") + " --confusion-norm raw -o " + q(d / "r.csv"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto rows = parse_scores(read_text(d / "r.csv"));
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0].at("condition"), "");
  EXPECT_EQ(rows[0].at("overspeed_segments"), "");  // v unknown
  EXPECT_NE(read_text(d / "r.csv.meta.json").find("\"source\": \"none\""), std::string::npos);
}

TEST(ScoreCli, LenientModeListsRejectsAndItsAccountAddsUp) {
  TempDir d;
  std::string log = good_log();
  log += "P03,adaptive,1,exaggerating,main,right,0,0.5,0.25\n";  // line 35
  log += "P03,adaptive,1,exaggerating,main,right,1,0.6,0.25\n";
  log += "P03,adaptive,1,exaggerating,main,right,1,0.7,0.25\n";  // line 37: time repeats
  log += "P03,adaptive,1,exaggerating,main,right,2,0.7,0.25\n";
  log += "P04,adaptive,1,exaggerating,main,right,0,0.5,0.25\n";  // one sample only
  write_text(d / "log.csv", log);
  const auto r = run_feint("score " + q(d / "log.csv") + " --on-error skip --rejects " +
                           q(d / "rej.csv") + " -o " + q(d / "s.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("38 rows read from 1 file(s), 3 trials scored, 2 rejected (list in "),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rej.csv"), std::string::npos) << r.err;
  const auto rows = parse_scores(read_text(d / "s.csv"));
  ASSERT_EQ(rows.size(), 3U);
  const auto rejects = parse_scores(read_text(d / "rej.csv"));
  ASSERT_EQ(rejects.size(), 2U);
  EXPECT_EQ(rejects[0].at("line"), "37");
  EXPECT_EQ(rejects[0].at("participant"), "P03");
  EXPECT_EQ(rejects[0].at("rows"), "4");
  EXPECT_NE(rejects[0].at("reason").find("log.csv:37: column 't': 1 is not after the previous "
                                         "sample's 1"), std::string::npos) << rejects[0].at("reason");
  EXPECT_NE(rejects[1].at("reason").find("a trial needs at least 2"), std::string::npos);
  // rows read = rows in scored trials + rows in rejected trials.
  long scored_rows = 0, rejected_rows = 0;
  for (const auto& row : rows) scored_rows += std::stol(row.at("n_samples"));
  for (const auto& row : rejects) rejected_rows += std::stol(row.at("rows"));
  EXPECT_EQ(scored_rows + rejected_rows, 38);
  const auto meta = read_text(d / "s.csv.meta.json");
  EXPECT_NE(meta.find("\"rows_scored\": 33, \"rows_rejected\": 5"), std::string::npos) << meta;
  EXPECT_NE(meta.find("\"on_error\": \"skip\""), std::string::npos);
}

TEST(ScoreCli, LenientDefaultRejectsPathAndZeroValidTrialsIsAnError) {
  TempDir d;
  write_text(d / "log.csv", good_log());
  auto r = run_feint("score " + q(d / "log.csv") + " --on-error skip -o " + q(d / "s.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(d / "s.csv.rejects.csv"), "file,line,participant,condition,iteration,rows,reason\n");

  write_text(d / "bad.csv", kHeader + "P1,a,1,s,m,right,0,2,0.25\nP1,a,1,s,m,right,1,2,0.25\n");
  fs::create_directories(d / "out");
  r = run_feint("score " + q(d / "bad.csv") + " --on-error skip --rejects " + q(d / "rej.csv") +
                " -o " + q(d / "out" / "s.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no valid trial: 2 rows read, all 1 trial(s) rejected"), std::string::npos)
      << r.err;
  EXPECT_TRUE(listing(d / "out").empty());
  EXPECT_NE(read_text(d / "rej.csv").find("'pad': 2 is outside"), std::string::npos);

  write_text(d / "empty.csv", kHeader);
  r = run_feint("score " + q(d / "empty.csv") + " -o " + q(d / "out" / "s.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("no valid trial"), std::string::npos) << r.err;
  EXPECT_TRUE(listing(d / "out").empty());
}

TEST(ScoreCli, ReappearingTrialNamesBothPlacesUnlessUnsorted) {
  TempDir d;
  const std::string first = trial_rows("P01,adaptive,1", "right", {0, 1, 2, 3, 4, 5}, {0.5, 0.25, 0, 0, 0, 0});
  const std::string rest = trial_rows("P01,adaptive,1", "right", {6, 7, 8, 9, 10}, {0, 0.25, 0.5, 0.75, 1});
  write_text(d / "log.csv", kHeader + first + trial_rows("P01,adaptive,2", "right", kT10, kMuA) + rest);
  auto r = run_feint("score " + q(d / "log.csv") + " -o " + q(d / "s.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("log.csv:19: rows of this trial already appeared at "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("log.csv:2 "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(trial P01/adaptive/1)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "s.csv"));
  r = run_feint("score " + q(d / "log.csv") + " --unsorted -o " + q(d / "s.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = parse_scores(read_text(d / "s.csv"));
  ASSERT_EQ(rows.size(), 2U);
  EXPECT_NEAR(num(rows[0].at("error")), 115.0 / 144, 1e-12);  // regrouped = example B

  // A trial split over two files.
  write_text(d / "split" / "a.csv", kHeader + first);
  write_text(d / "split" / "b.csv", kHeader + rest);
  r = run_feint("score " + q(d / "split") + " -o " + q(d / "s2.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("b.csv:2: rows of this trial already appeared at "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a.csv:2"), std::string::npos) << r.err;
  r = run_feint("score " + q(d / "split") + " --unsorted -o " + q(d / "s2.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(num(parse_scores(read_text(d / "s2.csv"))[0].at("error")), 115.0 / 144, 1e-12);
}

TEST(ScoreCli, ReadsDirectoriesGlobsGzipStdinMappedColumnsAndDelimiters) {
  TempDir d;
  write_text(d / "logs" / "p1.csv", kHeader + trial_rows("P01,adaptive,1", "right", kT10, kMuB));
  const std::string p2 = kHeader + trial_rows("P02,adaptive,1", "right", kT10, kMuA);
  gzFile f = gzopen((d / "logs" / "p2.csv.gz").c_str(), "wb");
  gzwrite(f, p2.data(), static_cast<unsigned>(p2.size()));
  gzclose(f);
  auto r = run_feint("score " + q(d / "logs") + " -o -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = parse_scores(r.out);
  ASSERT_EQ(rows.size(), 2U);
  EXPECT_EQ(rows[1].at("participant"), "P02");
  EXPECT_FALSE(fs::exists(d / "-.meta.json"));

  r = run_feint("score " + shell_quote((d / "logs").string() + "/*.gz") + " -o -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(parse_scores(r.out).size(), 1U);

  r = run_feint("score - -o -", read_text(d / "logs" / "p1.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(num(parse_scores(r.out)[0].at("error")), 115.0 / 144, 1e-12);

  // The study's own names and separator.
  std::string own = "Subject;Block;Round;Goal;Time;Knob\n";
  for (std::size_t i = 0; i < kT10.size(); ++i) {
    own += "S9;adaptive;4;right;" + feint::io::format_double(kT10[i]) + ";" +
           feint::io::format_double(kMuB[i]) + "\n";
  }
  write_text(d / "own.csv", own);
  r = run_feint("score " + q(d / "own.csv") + " --map participant=subject --map condition=Block "
                "--map iteration=round --map target=goal --map t=time --map pad=knob "
                "--delimiter ';' --confusion-norm speed --pad-speed 0.25 -o " + q(d / "own_scores.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  rows = parse_scores(read_text(d / "own_scores.csv"));
  ASSERT_EQ(rows.size(), 1U);
  EXPECT_EQ(rows[0].at("participant"), "S9");
  EXPECT_EQ(rows[0].at("iteration"), "4");
  EXPECT_NEAR(num(rows[0].at("confusion")), 217.0 / 360, 1e-12);
  EXPECT_NE(read_text(d / "own_scores.csv.meta.json").find("\"pad\": \"knob\""), std::string::npos);
  // A mapped column that is not there.
  r = run_feint("score " + q(d / "own.csv") + " --map participant=subject --map condition=Block "
                "--map iteration=round --map target=goal --map t=time --map pad=slider "
                "--pad-speed 1 -o " + q(d / "x.csv"));
  EXPECT_EQ(r.exit_code, 65);
  EXPECT_NE(r.err.find("own.csv:1: no column 'slider' (given by --map pad=slider"), std::string::npos)
      << r.err;
}

TEST(ScoreCli, ExampleDataSetScores) {
  const fs::path example = fs::path(FEINT_SOURCE_DIR) / "data" / "example";
  if (!fs::exists(example)) GTEST_SKIP() << "data/example not present";
  // `speed` confusion is bounded in [0, 1] (raw, the default, is not).
  const auto r = run_feint("score " + q(example) + " --confusion-norm speed -o -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = parse_scores(r.out);
  EXPECT_GE(rows.size(), 80U);
  for (const auto& row : rows) {
    const double e = num(row.at("error")), c = num(row.at("confusion"));
    EXPECT_GE(e, 0);
    EXPECT_LE(e, 1);
    EXPECT_GE(c, 0);
    EXPECT_LE(c, 1);
  }
}
