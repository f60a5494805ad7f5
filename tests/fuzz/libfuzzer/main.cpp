// libFuzzer entry: built by tests/fuzz/run.sh with -DFEINT_FUZZ_TARGET=<name of a harness function>.
#include <cstddef>
#include <cstdint>

#include "../harness.hpp"

#ifndef FEINT_FUZZ_TARGET
#error "define FEINT_FUZZ_TARGET (number, trace, scores, csv or questionnaire)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return feint::fuzz::FEINT_FUZZ_TARGET(data, size);
}
