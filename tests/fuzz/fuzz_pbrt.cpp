// libFuzzer harness for the pbrt-v4 loader: parse_pbrt on the bytes as though they were scratch/input.pbrt, so
// Include, Import, plymesh and spectrum-file names resolve against the scratch folder and its fixtures
// (fixture_include.pbrt, fixture.ply, fixture.ply.gz, fixture.spd). A kiln::Error is the expected outcome for bad
// input; any other exception, crash, leak, hang or sanitizer report is a finding. Built by cmake/KilnFuzz.cmake
// (clang, -DKILN_FUZZ=ON), run by .ci/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return kiln::fuzz::harness_input(kiln::fuzz::Loader::Pbrt, data, size);
}
