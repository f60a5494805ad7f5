// tests/fuzz/harness.hpp - one entry function per fuzz target, callable without libFuzzer.
//
// Each function takes one input (bytes), runs a loader on it and checks what must hold for ANY
// input: the loader either returns data that satisfies the contract or throws a feint::Error; it
// never crashes, hangs or returns a value outside the contract. A broken invariant calls
// std::abort() (libFuzzer reports it; the gtest replay dies). libfuzzer/main.cpp turns one of them
// into LLVMFuzzerTestOneInput; test_replay.cpp feeds every committed corpus file to each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace feint::fuzz {

/// Differential: io::parse_double (and the loaders' fast path) against strtod in the C locale.
int number(const std::uint8_t* data, std::size_t size);
/// io::TraceReader (strict, lenient, unsorted) and the metrics of every trial it hands out.
int trace(const std::uint8_t* data, std::size_t size);
/// io::load_scores and io::load_numeric_column.
int scores(const std::uint8_t* data, std::size_t size);
/// io::CsvReader (detected and fixed delimiters).
int csv(const std::uint8_t* data, std::size_t size);
/// io::load_questionnaire (automatic, long and wide layouts).
int questionnaire(const std::uint8_t* data, std::size_t size);

namespace detail {
/// A path whose content is `data` (an in-memory file, rewritten on every call).
std::string as_file(const std::uint8_t* data, std::size_t size);
/// Aborts with `what` on stderr when `ok` is false.
void check(bool ok, const char* what);
}  // namespace detail

}  // namespace feint::fuzz
