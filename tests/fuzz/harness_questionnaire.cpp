// The questionnaire loader through its public API only (include/feint/io/questionnaire.hpp).
#include <string>

#include "feint/error.hpp"
#include "feint/io/questionnaire.hpp"
#include "harness.hpp"

namespace feint::fuzz {

int questionnaire(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  using detail::check;
  const std::string path = detail::as_file(data, size);
  for (const auto layout : {io::QuestionnaireLayout::automatic, io::QuestionnaireLayout::long_format,
                            io::QuestionnaireLayout::wide_format}) {
    try {
      io::QuestionnaireOptions opt;
      opt.layout = layout;
      const auto q = io::load_questionnaire(path, opt);
      check(q.participants.size() == q.conditions.size(), "a respondent without a condition");
      check(q.responses.size() == q.items.size(), "one response column per item");
      check(q.reversed.size() == q.items.size(), "one reverse flag per item");
      for (const auto& column : q.responses) {
        check(column.size() == q.respondents(), "one response per respondent");
        for (const auto& v : column) {
          check(!v || (*v >= q.scale_min && *v <= q.scale_max), "response outside the scale");
        }
      }
    } catch (const Error&) {
    }
  }
  return 0;
}

}  // namespace feint::fuzz
