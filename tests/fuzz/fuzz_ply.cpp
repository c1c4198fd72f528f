// libFuzzer harness for the PLY loader: parse_ply on the raw bytes (ASCII, binary little/big endian).
// A kiln::Error is the expected outcome for bad input; any other exception, crash, leak or sanitizer report is a
// finding. Built by cmake/KilnFuzz.cmake (clang, -DKILN_FUZZ=ON), run by .ci/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return kiln::fuzz::harness_input(kiln::fuzz::Loader::Ply, data, size);
}
