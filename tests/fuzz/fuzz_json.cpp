// libFuzzer harness for the CS171 JSON loader: load_cs171_json on the bytes written to a scratch file (it has no
// in-memory entry point); obj_file_path references resolve against the scratch folder and its fixtures.
// A kiln::Error is the expected outcome for bad input; any other exception, crash, leak or sanitizer report is a
// finding. Built by cmake/KilnFuzz.cmake (clang, -DKILN_FUZZ=ON), run by .ci/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return kiln::fuzz::harness_input(kiln::fuzz::Loader::Json, data, size);
}
