// The RFC 4180 reader: every record it returns is consistent with its own counters.
#include <string>

#include "feint/error.hpp"
#include "feint/io/csv.hpp"
#include "harness.hpp"

namespace feint::fuzz {

int csv(const std::uint8_t* data, std::size_t size) {
  if (size > 1 << 16) return 0;
  using detail::check;
  const std::string path = detail::as_file(data, size);
  for (const char delimiter : {'\0', ',', ';', '\t'}) {
    for (const bool width : {true, false}) {
      try {
        io::CsvOptions opt;
        opt.delimiter = delimiter;
        opt.require_header_width = width;
        io::CsvReader r(path, opt);
        check(!r.header().empty(), "no header fields");
        std::uint64_t records = 0, last_line = r.line();
        while (r.next()) {
          ++records;
          check(r.records() == records, "records() miscounted");
          check(r.line() > last_line, "line numbers do not increase");
          last_line = r.line();
          if (width) check(r.fields().size() == r.header().size(), "wrong field count accepted");
          for (std::size_t i = 0; i < r.fields().size(); ++i) {
            check(r.field(i).data() == r.fields()[i].data(), "field() differs from fields()");
          }
        }
        check(r.bytes_consumed() <= size || r.compressed(), "consumed more than the input");
      } catch (const Error&) {
      }
    }
  }
  return 0;
}

}  // namespace feint::fuzz
