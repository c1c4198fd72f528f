// libFuzzer harness for the OBJ loader: parse_obj on the raw text (pre-scan validation, then tinyobjloader).
// A kiln::Error is the expected outcome for bad input; any other exception, crash, leak or sanitizer report is a
// finding. Built by cmake/KilnFuzz.cmake (clang, -DKILN_FUZZ=ON), run by .ci/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return kiln::fuzz::harness_input(kiln::fuzz::Loader::Obj, data, size);
}
