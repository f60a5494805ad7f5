// Likert questionnaire loader: layouts, survey exports, label maps, reverse coding, bad input.
#include "feint/io/questionnaire.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "feint/error.hpp"

namespace fs = std::filesystem;
using feint::InvalidData;
using feint::UsageError;
using feint::io::load_questionnaire;
using feint::io::Questionnaire;
using feint::io::QuestionnaireLayout;
using feint::io::QuestionnaireOptions;

namespace {

std::string data(const std::string& name) {
  return std::string(FEINT_TEST_DATA_DIR) + "/likert/" + name;
}

/// A temporary CSV file with the given content, removed at scope exit.
class TempCsv {
 public:
  explicit TempCsv(const std::string& content) {
    static int counter = 0;
    path_ = (fs::temp_directory_path() / ("feint-questionnaire-" + std::to_string(::getpid()) +
                                          "-" + std::to_string(counter++) + ".csv"))
                .string();
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempCsv() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// The message of the InvalidData that loading `content` throws ("" when none is thrown).
std::string invalid_message(const std::string& content, QuestionnaireOptions options = {}) {
  TempCsv f(content);
  try {
    load_questionnaire(f.path(), options);
  } catch (const InvalidData& e) {
    std::string m = e.what();
    // Strip the temporary path so the expectation reads as the message without the file name.
    if (m.rfind(f.path(), 0) == 0) m = "FILE" + m.substr(f.path().size());
    return m;
  }
  return "";
}

std::optional<int> at(const Questionnaire& q, const std::string& item, const std::string& who) {
  const auto i = q.item_index(item);
  EXPECT_TRUE(i.has_value()) << item;
  for (std::size_t r = 0; r < q.respondents(); ++r) {
    if (q.participants[r] == who) return q.responses[*i][r];
  }
  ADD_FAILURE() << "no respondent " << who;
  return std::nullopt;
}

}  // namespace

TEST(Questionnaire, WideLayoutIsDetectedFromTheHeader) {
  const auto q = load_questionnaire(data("wide.csv"));
  EXPECT_EQ(q.layout, QuestionnaireLayout::wide_format);
  EXPECT_FALSE(q.qualtrics);
  EXPECT_TRUE(q.has_condition);
  ASSERT_EQ(q.items,
            (std::vector<std::string>{"entertainment", "deception", "intelligence", "trust"}));
  EXPECT_EQ(q.respondents(), 10u);
  EXPECT_EQ(q.rows_read, 10u);
  EXPECT_EQ(q.condition_names(), (std::vector<std::string>{"adaptive", "random"}));
  EXPECT_EQ(at(q, "trust", "P04"), 1);
  EXPECT_EQ(at(q, "deception", "P03"), std::nullopt);  // empty cell = missing
  EXPECT_EQ(q.missing(*q.item_index("deception")), 1u);
  EXPECT_EQ(q.missing(*q.item_index("entertainment")), 0u);
  EXPECT_EQ(q.text_answers_mapped, 0u);
  EXPECT_EQ(q.label_map, "");
}

TEST(Questionnaire, LongLayoutHoldsTheSameDataAsWide) {
  const auto wide = load_questionnaire(data("wide.csv"));
  const auto lng = load_questionnaire(data("long.csv"));
  EXPECT_EQ(lng.layout, QuestionnaireLayout::long_format);
  EXPECT_EQ(lng.items, wide.items);
  EXPECT_EQ(lng.participants, wide.participants);
  EXPECT_EQ(lng.conditions, wide.conditions);
  EXPECT_EQ(lng.responses, wide.responses);
  // P07 has no row for intelligence at all: missing, counted like an empty answer.
  EXPECT_EQ(at(lng, "intelligence", "P07"), std::nullopt);
  EXPECT_EQ(lng.missing(*lng.item_index("intelligence")), 1u);
  EXPECT_EQ(lng.rows_read, 39u);
}

TEST(Questionnaire, LayoutCanBeForced) {
  QuestionnaireOptions o;
  o.layout = QuestionnaireLayout::long_format;
  TempCsv f("participant,a,b\nP1,1,2\n");
  try {
    load_questionnaire(f.path(), o);
    FAIL() << "expected InvalidData";
  } catch (const InvalidData& e) {
    EXPECT_NE(std::string(e.what()).find("the long layout needs columns 'item' and 'response'"),
              std::string::npos)
        << e.what();
  }
  // A wide file whose items happen to be called item and response.
  TempCsv g("participant,item,response\nP1,3,4\n");
  o.layout = QuestionnaireLayout::wide_format;
  const auto q = load_questionnaire(g.path(), o);
  EXPECT_EQ(q.items, (std::vector<std::string>{"item", "response"}));
  EXPECT_EQ(q.responses[1][0], 4);
}

TEST(Questionnaire, QualtricsHeaderRowsAreSkippedAndTextMappedByTheBuiltInMap) {
  const auto q = load_questionnaire(data("qualtrics.csv"));
  EXPECT_TRUE(q.qualtrics);
  EXPECT_EQ(q.layout, QuestionnaireLayout::wide_format);
  // Metadata columns are not items; ResponseId is the respondent id.
  EXPECT_EQ(q.items, (std::vector<std::string>{"Q1", "Q2", "Q3"}));
  EXPECT_EQ(q.participants, (std::vector<std::string>{"R_1a", "R_2b", "R_3c", "R_4d"}));
  EXPECT_EQ(q.rows_read, 4u);
  EXPECT_EQ(q.label_map, "built-in 7-point agree");
  EXPECT_EQ(q.text_answers_mapped, 11u);
  EXPECT_EQ(at(q, "Q1", "R_1a"), 7);  // Strongly agree
  EXPECT_EQ(at(q, "Q1", "R_4d"), 7);  // STRONGLY AGREE: case-insensitive
  EXPECT_EQ(at(q, "Q2", "R_1a"), 5);  // Somewhat agree
  EXPECT_EQ(at(q, "Q2", "R_3c"), 4);  // Neither agree nor disagree
  EXPECT_EQ(at(q, "Q3", "R_1a"), 2);  // Disagree
  EXPECT_EQ(at(q, "Q3", "R_2b"), 1);  // " strongly disagree ": trimmed
  EXPECT_EQ(at(q, "Q3", "R_3c"), std::nullopt);
  EXPECT_EQ(at(q, "Q3", "R_4d"), 3);  // Somewhat disagree
}

TEST(Questionnaire, BuiltInFivePointMapFollowsTheScale) {
  QuestionnaireOptions o;
  o.scale_min = 1;
  o.scale_max = 5;
  TempCsv f(
      "participant,x\nP1,Strongly disagree\nP2,Somewhat disagree\nP3,Neutral\nP4,agree\n"
      "P5,Strongly Agree\n");
  const auto q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.label_map, "built-in 5-point agree");
  EXPECT_EQ(q.responses[0], (std::vector<std::optional<int>>{1, 2, 3, 4, 5}));
  // A 6-point scale has no built-in map: text is invalid and the message says what to do.
  o.scale_max = 6;
  EXPECT_EQ(invalid_message("participant,x\nP1,Agree\n", o),
            "FILE:2: column 'x': 'Agree' is not a number or a known label (participant P1); "
            "expected a whole number 1-6 (use --labels to map text answers)");
}

TEST(Questionnaire, UserLabelsReplaceTheBuiltInMap) {
  QuestionnaireOptions o;
  o.labels = feint::io::parse_label_map("Not at all=1,A little=2,\"Some, maybe\"=4,Very much=7");
  ASSERT_EQ(o.labels.size(), 4u);
  EXPECT_EQ(o.labels[2].text, "Some, maybe");
  TempCsv f("participant,fun\nP1,a little\nP2,\"Some, maybe\"\nP3,6\n");
  const auto q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.label_map, "user");
  EXPECT_EQ(q.text_answers_mapped, 2u);
  EXPECT_EQ(q.responses[0], (std::vector<std::optional<int>>{2, 4, 6}));
  // The built-in labels are off once the user gives a map.
  EXPECT_EQ(invalid_message("participant,fun\nP1,Agree\n", o),
            "FILE:2: column 'fun': 'Agree' is not a number or a known label (participant P1); "
            "expected a whole number 1-7 or a label of the user map");
}

TEST(Questionnaire, ReverseCodingUsesMinPlusMaxMinusX) {
  QuestionnaireOptions o;
  o.reverse = {"TRUST"};  // case-insensitive
  const auto q = load_questionnaire(data("wide.csv"), o);
  const auto t = *q.item_index("trust");
  EXPECT_TRUE(q.reversed[t]);
  EXPECT_FALSE(q.reversed[0]);
  EXPECT_EQ(at(q, "trust", "P04"), 7);  // 1 + 7 - 1
  EXPECT_EQ(at(q, "trust", "P08"), 3);  // 1 + 7 - 5
  // Missing stays missing; other scales use their own bounds.
  o.reverse = {"deception"};
  o.scale_min = 0;
  o.scale_max = 10;
  const auto r = load_questionnaire(data("wide.csv"), o);
  EXPECT_EQ(at(r, "deception", "P01"), 5);  // 0 + 10 - 5
  EXPECT_EQ(at(r, "deception", "P09"), 8);
  EXPECT_EQ(at(r, "deception", "P03"), std::nullopt);
}

TEST(Questionnaire, ItemsAndStudyColumnNamesAreSelectable) {
  TempCsv f("Subject;Group;Timestamp;fun;notes;trust\nS1;A;x;5;hello;2\nS2;B;y;;;3\n");
  QuestionnaireOptions o;
  o.id_column = "subject";
  o.condition_column = "GROUP";
  o.items = {"trust", "fun"};
  const auto q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.items, (std::vector<std::string>{"trust", "fun"}));
  EXPECT_EQ(q.participants, (std::vector<std::string>{"S1", "S2"}));
  EXPECT_EQ(q.conditions, (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(q.responses[1], (std::vector<std::optional<int>>{5, std::nullopt}));
  o.items = {"trust", "nope"};
  EXPECT_THROW(load_questionnaire(f.path(), o), UsageError);
}

TEST(Questionnaire, OutOfRangeResponseNamesFileLineColumnValueAndParticipant) {
  EXPECT_EQ(invalid_message("participant,trust\nP01,3\nP07,9\n"),
            "FILE:3: column 'trust': 9 is outside the scale 1-7 (participant P07)");
  EXPECT_EQ(invalid_message("participant,trust\nP07,0\n"),
            "FILE:2: column 'trust': 0 is outside the scale 1-7 (participant P07)");
  EXPECT_EQ(invalid_message("participant,condition,trust\nP07,adaptive,-2\n"),
            "FILE:2: column 'trust': -2 is outside the scale 1-7 (participant P07, condition "
            "adaptive)");
}

TEST(Questionnaire, FractionalResponseIsInvalid) {
  EXPECT_EQ(invalid_message("participant,trust\nP07,4.5\n"),
            "FILE:2: column 'trust': 4.5 is not a whole number on the scale 1-7 (participant P07)");
  // 4.0 is the whole number 4.
  TempCsv f("participant,trust\nP07,4.0\n");
  EXPECT_EQ(load_questionnaire(f.path()).responses[0][0], 4);
}

TEST(Questionnaire, LongLayoutErrorsNameTheItem) {
  EXPECT_EQ(invalid_message("participant,item,response\nP07,trust,8\n"),
            "FILE:2: column 'response': 8 is outside the scale 1-7 (participant P07, item trust)");
  EXPECT_EQ(
      invalid_message("participant,item,response\nP07,trust,nan\n"),
      "FILE:2: column 'response': 'nan' is not a number or a known label (participant P07, "
      "item trust); expected a whole number 1-7 or a label of the built-in 7-point agree map");
  EXPECT_EQ(invalid_message("participant,item,response\nP07,trust,3\nP08,trust,3\nP07,trust,4\n"),
            "FILE:4: participant P07 answered item 'trust' twice (first at line 2)");
  EXPECT_EQ(invalid_message("participant,item,response\nP07,,3\n"),
            "FILE:2: column 'item': empty item name (participant P07)");
}

TEST(Questionnaire, DuplicateRespondentAndEmptyKeysAreInvalid) {
  EXPECT_EQ(invalid_message("participant,trust\nP01,3\nP02,4\nP01,5\n"),
            "FILE:4: participant P01 has a second row (first at line 2); the wide layout has one "
            "row per respondent");
  EXPECT_EQ(invalid_message("participant,trust\n ,3\n"),
            "FILE:2: column 'participant': empty respondent id");
  EXPECT_EQ(invalid_message("participant,condition,trust\nP01,,3\n"),
            "FILE:2: column 'condition': empty condition (participant P01)");
  // The same participant in two conditions is two respondents (within-subject designs).
  TempCsv f("participant,condition,trust\nP01,a,3\nP01,b,5\n");
  EXPECT_EQ(load_questionnaire(f.path()).respondents(), 2u);
}

TEST(Questionnaire, MissingColumnsAndEmptyFilesAreInvalid) {
  EXPECT_EQ(invalid_message("who,trust\nP01,3\n"),
            "FILE: no column 'participant' (the respondent id); name the study's column with "
            "--id-column (columns: who, trust)");
  EXPECT_EQ(invalid_message("participant,trust\n"),
            "FILE: no responses (a header but no data rows)");
  EXPECT_EQ(invalid_message("participant,condition\nP1,a\n"),
            "FILE: no item columns (columns: participant, condition)");
  EXPECT_EQ(invalid_message("participant,trust\nP01,3,4\n"),
            "FILE:2: 3 fields where the header has 2");
}

TEST(Questionnaire, UnknownReverseItemIsAUsageError) {
  QuestionnaireOptions o;
  o.reverse = {"honesty"};
  try {
    load_questionnaire(data("wide.csv"), o);
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(),
                 "--reverse: no item 'honesty' (items: entertainment, deception, intelligence, "
                 "trust)");
  }
}

TEST(Questionnaire, ScaleAndLabelOptionsParse) {
  using feint::io::parse_scale;
  EXPECT_EQ(parse_scale("1-7"), std::make_pair(1, 7));
  EXPECT_EQ(parse_scale(" 0-10 "), std::make_pair(0, 10));
  EXPECT_EQ(parse_scale("-3-3"), std::make_pair(-3, 3));
  EXPECT_EQ(parse_scale("-5--1"), std::make_pair(-5, -1));
  EXPECT_THROW(parse_scale("7-1"), UsageError);
  EXPECT_THROW(parse_scale("4-4"), UsageError);
  EXPECT_THROW(parse_scale("1-7.5"), UsageError);
  EXPECT_THROW(parse_scale("7"), UsageError);
  EXPECT_THROW(parse_scale("a-b"), UsageError);
  EXPECT_THROW(feint::io::parse_label_map("Agree"), UsageError);
  EXPECT_THROW(feint::io::parse_label_map("Agree=x"), UsageError);
  EXPECT_THROW(feint::io::parse_label_map("Agree=1,agree=2"), UsageError);
  QuestionnaireOptions o;
  o.labels = {{"Agree", 9}};
  EXPECT_THROW(load_questionnaire(data("wide.csv"), o), UsageError);  // label outside the scale
  EXPECT_EQ(feint::io::builtin_agree_labels(1, 6).size(), 0u);
  EXPECT_EQ(feint::io::builtin_agree_labels(0, 6).front().value, 0);
  EXPECT_EQ(feint::io::builtin_agree_labels(0, 6).back().value, 6);
}

TEST(Questionnaire, ItemsSelectAndOrderLongLayoutItems) {
  QuestionnaireOptions o;
  o.items = {"Trust", "entertainment"};
  TempCsv f(
      "participant,item,response\nP1,entertainment,5\nP1,notes,free text\nP1,trust,2\n"
      "P2,trust,3\n");
  const auto q = load_questionnaire(f.path(), o);
  EXPECT_EQ(q.items, (std::vector<std::string>{"trust", "entertainment"}));
  EXPECT_EQ(q.responses[0], (std::vector<std::optional<int>>{2, 3}));
  EXPECT_EQ(q.responses[1], (std::vector<std::optional<int>>{5, std::nullopt}));
  EXPECT_EQ(q.rows_read, 4u);
  o.items = {"honesty"};
  EXPECT_THROW(load_questionnaire(f.path(), o), UsageError);
}

TEST(Questionnaire, LongScalesAndDuplicateItemColumns) {
  EXPECT_EQ(feint::io::parse_scale("0-100"), std::make_pair(0, 100));
  EXPECT_THROW(feint::io::parse_scale("0-101"), UsageError);
  QuestionnaireOptions o;
  o.scale_min = 0;
  o.scale_max = 100;
  TempCsv f("participant,vas\nP1,73\nP2,100\n");
  EXPECT_EQ(load_questionnaire(f.path(), o).responses[0],
            (std::vector<std::optional<int>>{73, 100}));
  EXPECT_EQ(invalid_message("participant,trust,Trust\nP1,3,4\n"),
            "FILE: item column 'trust' appears twice in the header");
}
