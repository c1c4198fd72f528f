// libFuzzer harness for the OBJ loader: parse_obj on the raw text (pre-scan validation, then tinyobjloader).
// A kiln::Error is the expected outcome for bad input; any other exception, crash, leak or sanitizer report is a
// finding. Built by cmake/KilnFuzz.cmake (clang, -DKILN_FUZZ=ON), run by .ci/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

// tinyobjloader's implementation compiled into the harness: these definitions take precedence over the
// uninstrumented shared library's, so the fuzzer gets coverage feedback, and ASan sees the memory accesses, inside
// the OBJ parser too. cmake/KilnFuzz.cmake gives this file the library's compile definitions (real_t = double).
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return kiln::fuzz::harness_input(kiln::fuzz::Loader::Obj, data, size);
}
