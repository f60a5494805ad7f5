// Questionnaire loader: a real Qualtrics export (preview, test, spam and unfinished
// responses are not participants), item renaming (--items name=Q5_1), and loading in memory linear
// in the file (a long file whose items are all different must not build a rows x rows matrix).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"

namespace fs = std::filesystem;
using feint::InvalidData;
using feint::UsageError;
using feint::io::load_questionnaire;
using feint::io::Questionnaire;
using feint::io::QuestionnaireOptions;

namespace {

class TempCsv {
 public:
  explicit TempCsv(const std::string& content) {
    static int counter = 0;
    path_ = (fs::temp_directory_path() / ("feint-qexport-" + std::to_string(::getpid()) + "-" +
                                          std::to_string(counter++) + ".csv"))
                .string();
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempCsv() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A Qualtrics export (three header rows) with the usual metadata columns.
std::string qualtrics(const std::string& rows) {
  return "StartDate,EndDate,Status,Progress,Duration (in seconds),Finished,ResponseId,cond,Q5_1,"
         "Q5_2\n"
         "Start Date,End Date,Response Type,Progress,Duration (in seconds),Finished,Response ID,"
         "cond,I trusted the robot.,It was fun.\n"
         "\"{\"\"ImportId\"\":\"\"startDate\"\"}\",\"{\"\"ImportId\"\":\"\"endDate\"\"}\","
         "\"{\"\"ImportId\"\":\"\"status\"\"}\",\"{\"\"ImportId\"\":\"\"progress\"\"}\","
         "\"{\"\"ImportId\"\":\"\"duration\"\"}\",\"{\"\"ImportId\"\":\"\"finished\"\"}\","
         "\"{\"\"ImportId\"\":\"\"_recordId\"\"}\",\"{\"\"ImportId\"\":\"\"cond\"\"}\","
         "\"{\"\"ImportId\"\":\"\"QID5_1\"\"}\",\"{\"\"ImportId\"\":\"\"QID5_2\"\"}\"\n" +
         rows;
}

const std::string kRows =
    "2026-05-01,2026-05-01,IP Address,100,360,True,R_1,a,5,6\n"
    "2026-05-01,2026-05-01,Survey Preview,100,30,True,R_prev,a,7,7\n"
    "2026-05-01,2026-05-01,IP Address,40,100,False,R_half,b,1,\n"
    "2026-05-01,2026-05-01,Spam,100,20,True,R_spam,b,7,7\n"
    "2026-05-01,2026-05-01,IP Address,100,300,True,R_2,b,3,4\n"
    "2026-05-01,2026-05-01,Survey Test,100,10,True,R_test,a,1,1\n"
    "2026-05-01,2026-05-01,IP Address,100,200,True,R_3,a,4,2\n";

long peak_rss_kb() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

TEST(QualtricsExport, PreviewsTestsSpamAndUnfinishedResponsesAreNotParticipants) {
  TempCsv f(qualtrics(kRows));
  QuestionnaireOptions o;
  o.condition_column = "cond";
  const Questionnaire q = load_questionnaire(f.path(), o);
  EXPECT_TRUE(q.qualtrics);
  ASSERT_EQ(q.respondents(), 3u);
  EXPECT_EQ(q.participants, (std::vector<std::string>{"R_1", "R_2", "R_3"}));
  ASSERT_EQ(q.excluded.size(), 4u);
  EXPECT_EQ(q.excluded[0].id, "R_prev");
  EXPECT_EQ(q.excluded[0].reason, "Survey Preview");
  EXPECT_EQ(q.excluded[1].id, "R_half");
  EXPECT_EQ(q.excluded[1].reason, "unfinished (Finished False, Progress 40)");
  EXPECT_EQ(q.excluded[2].id, "R_spam");
  EXPECT_EQ(q.excluded[3].reason, "Survey Test");
  EXPECT_EQ(q.rows_read, 7u);
  EXPECT_NE(feint::io::describe_exclusions(q).find("4 responses of the survey export excluded"),
            std::string::npos)
      << feint::io::describe_exclusions(q);
}

TEST(QualtricsExport, OptionsKeepUnfinishedResponsesAndPreviews) {
  TempCsv f(qualtrics(kRows));
  QuestionnaireOptions o;
  o.condition_column = "cond";
  o.keep_unfinished = true;
  Questionnaire q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.respondents(), 4u);
  EXPECT_EQ(q.excluded.size(), 3u);
  o.keep_previews = true;
  q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.respondents(), 7u);
  EXPECT_TRUE(q.excluded.empty());
  EXPECT_EQ(feint::io::describe_exclusions(q), "");
}

TEST(QualtricsExport, NumericStatusCodesAndFinishedAsZeroOne) {
  // Qualtrics' "numeric values" export: Status 1 = preview, 2 = test, 8 = spam; Finished 1/0.
  TempCsv f(
      qualtrics("d,d,0,100,1,1,R_1,a,5,6\nd,d,1,100,1,1,R_p,a,5,6\nd,d,0,99,1,0,R_u,a,5,\n"
                "d,d,4,100,1,1,R_imported,b,2,3\nd,d,8,100,1,1,R_s,b,1,1\n"));
  QuestionnaireOptions o;
  o.condition_column = "cond";
  const Questionnaire q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.participants, (std::vector<std::string>{"R_1", "R_imported"}));
  EXPECT_EQ(q.excluded.size(), 3u);
}

TEST(QualtricsExport, ItemsAreRenamedByNameEqualsColumn) {
  TempCsv f(qualtrics(kRows));
  QuestionnaireOptions o;
  o.condition_column = "cond";
  o.items = {"trust=Q5_1", "fun=Q5_2"};
  o.reverse = {"fun"};
  const Questionnaire q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.items, (std::vector<std::string>{"trust", "fun"}));
  EXPECT_EQ(q.item_columns, (std::vector<std::string>{"Q5_1", "Q5_2"}));
  ASSERT_EQ(q.respondents(), 3u);
  EXPECT_EQ(q.responses[0][0], 5);
  EXPECT_EQ(q.responses[1][0], 8 - 6);  // reversed on 1-7
  EXPECT_THROW(load_questionnaire(f.path(),
                                  [&] {
                                    auto b = o;
                                    b.items = {"trust=Q9"};
                                    return b;
                                  }()),
               UsageError);
  EXPECT_THROW(load_questionnaire(f.path(),
                                  [&] {
                                    auto b = o;
                                    b.items = {"x=Q5_1", "x=Q5_2"};
                                    b.reverse.clear();
                                    return b;
                                  }()),
               UsageError);
}

TEST(LongLayout, ItemsAreRenamedToo) {
  TempCsv f("participant,item,response\nP1,Q5_1,3\nP1,Q5_2,4\nP2,Q5_1,5\nP2,Q5_2,6\n");
  QuestionnaireOptions o;
  o.items = {"fun=Q5_2", "trust=Q5_1"};
  const Questionnaire q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.items, (std::vector<std::string>{"fun", "trust"}));
  EXPECT_EQ(q.responses[0][1], 6);
  EXPECT_EQ(q.responses[1][0], 3);
}

TEST(LongLayout, AValidLongFileOf20000RowsLoadsInMemoryLinearInItsRows) {
  // 2,000 respondents x 10 items.
  std::ostringstream s;
  s << "participant,condition,item,response\n";
  for (int p = 0; p < 2000; ++p) {
    for (int i = 0; i < 10; ++i)
      s << "P" << p << "," << (p % 2 ? "a" : "b") << ",item" << i << "," << (p + i) % 7 + 1 << "\n";
  }
  TempCsv f(s.str());
  const long before = peak_rss_kb();
  const Questionnaire q = load_questionnaire(f.path());
  EXPECT_EQ(q.respondents(), 2000u);
  EXPECT_EQ(q.items.size(), 10u);
  EXPECT_EQ(q.rows_read, 20000u);
  EXPECT_LT(peak_rss_kb() - before, 64 * 1024) << "kB";
}

TEST(LongLayout, AllDifferentItemsAreRefusedWithoutARowsTimesRowsMatrix) {
  // 20,000 rows, each its own respondent and its own item (e.g. the wrong --item-column): the
  // dense items x respondents matrix would be 20,000 x 20,000 cells (3.2 GB). Loading must stay
  // linear in the rows: the loader refuses such a sparse reading with a message, within bounded
  // memory.
  std::ostringstream s;
  s << "participant,item,response\n";
  for (int r = 0; r < 20000; ++r)
    s << "P" << r << ",free text answer " << r << "," << r % 7 + 1 << "\n";
  TempCsv f(s.str());
  const long before = peak_rss_kb();
  try {
    load_questionnaire(f.path());
    ADD_FAILURE() << "expected InvalidData";
  } catch (const InvalidData& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("20000 items"), std::string::npos) << what;
    EXPECT_NE(what.find("--item-column"), std::string::npos) << what;
  }
  EXPECT_LT(peak_rss_kb() - before, 64 * 1024) << "kB";
}
