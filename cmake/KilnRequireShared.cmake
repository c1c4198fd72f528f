# KILN_REQUIRE_SHARED=ON (CI): the course data and the fuzzing toolchain are requirements, not options. Without
# them the tests that need them would report themselves skipped, and ctest counts a skip as a pass; so the
# configure stops here, naming everything that is missing. Off (the default), a developer without ../shared or
# clang gets those skips, each with a message.
include_guard(GLOBAL)
if(NOT KILN_REQUIRE_SHARED)
  return()
endif()

set(_missing "")
get_filename_component(_shared "${KILN_SHARED_DIR}" ABSOLUTE)
if(NOT IS_DIRECTORY "${_shared}/scenes/ceng795")
  list(APPEND _missing "the course scenes: KILN_SHARED_DIR=${_shared} has no scenes/ceng795 (set -DKILN_SHARED_DIR)")
endif()

# libFuzzer ships with clang's runtime (libclang-rt-14-dev): link a one-function harness to prove both are there.
find_program(KILN_CLANGXX NAMES clang++ clang++-14)
if(NOT KILN_CLANGXX)
  list(APPEND _missing "the fuzzing toolchain: clang++ not found (bash .ci/install-deps.sh installs clang)")
else()
  set(_probe_dir "${CMAKE_BINARY_DIR}/CMakeFiles/kiln_libfuzzer_probe")
  file(MAKE_DIRECTORY "${_probe_dir}")
  file(WRITE "${_probe_dir}/probe.cpp"
       "#include <cstddef>\n#include <cstdint>\nextern \"C\" int LLVMFuzzerTestOneInput(const uint8_t*, size_t) { return 0; }\n")
  execute_process(COMMAND "${KILN_CLANGXX}" -fsanitize=fuzzer "${_probe_dir}/probe.cpp" -o "${_probe_dir}/probe"
                  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  if(NOT _rc EQUAL 0)
    list(APPEND _missing "the fuzzing toolchain: ${KILN_CLANGXX} cannot link -fsanitize=fuzzer (install libclang-rt-14-dev)")
  endif()
endif()

if(_missing)
  list(JOIN _missing "\n  - " _list)
  message(FATAL_ERROR "KILN_REQUIRE_SHARED=ON but missing:\n  - ${_list}\n"
                      "Configure with -DKILN_REQUIRE_SHARED=OFF to skip the tests that need them instead.")
endif()
message(STATUS "KILN_REQUIRE_SHARED: course scenes at ${_shared}, fuzzing with ${KILN_CLANGXX}")
