# libFuzzer harnesses for the scene loaders (tests/fuzz/fuzz_<loader>.cpp -> target kiln_fuzz_<loader>).
# A no-op unless KILN_FUZZ=ON and the compiler is clang. When active, every Kiln target is compiled with
# -fsanitize=fuzzer-no-link,address,undefined (coverage feedback + ASan + UBSan, UBSan fatal), and the harnesses
# are linked with -fsanitize=fuzzer (libFuzzer's main). .ci/fuzz.sh configures, builds and runs them.
#
# Include it with the other modules, before the layers are defined (add_compile_options only reaches targets
# created after it):  include(KilnFuzz)
include_guard(GLOBAL)
option(KILN_FUZZ "Build the libFuzzer loader harnesses (clang only; instruments every target)" OFF)

if(NOT KILN_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(WARNING "KILN_FUZZ=ON needs clang (libFuzzer); ${CMAKE_CXX_COMPILER_ID} found, fuzz harnesses not built. "
                  "Configure with -DCMAKE_CXX_COMPILER=clang++.")
  return()
endif()
if(TARGET kiln_core)
  message(FATAL_ERROR "include(KilnFuzz) must come before the Kiln layers are defined, "
                      "otherwise they are built without coverage instrumentation")
endif()
if(KILN_SANITIZE STREQUAL "thread")
  message(FATAL_ERROR "KILN_FUZZ=ON uses AddressSanitizer; it cannot be combined with KILN_SANITIZE=thread")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/KilnWarnings.cmake")  # kiln_apply_warnings, whatever the include order

# Coverage instrumentation, ASan and UBSan on all code; the fuzzer runtime itself is linked into the harnesses only,
# so test executables (if built in the same tree) keep GoogleTest's main.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)

file(GLOB _kiln_fuzz_harnesses CONFIGURE_DEPENDS "${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_*.cpp")
foreach(_src IN LISTS _kiln_fuzz_harnesses)
  get_filename_component(_stem "${_src}" NAME_WE)
  string(REGEX REPLACE "^fuzz_" "" _loader "${_stem}")
  set(_tgt kiln_fuzz_${_loader})
  add_executable(${_tgt} "${_src}")
  target_link_libraries(${_tgt} PRIVATE kiln_scenes)  # defined later; resolved at generate time
  target_compile_features(${_tgt} PRIVATE cxx_std_20)
  target_link_options(${_tgt} PRIVATE -fsanitize=fuzzer)
  kiln_apply_warnings(${_tgt})
  if(_loader STREQUAL "obj")  # compiles tinyobjloader's implementation: needs the package's definitions
    target_link_libraries(${_tgt} PRIVATE kiln_tinyobjloader)
  endif()
  list(APPEND KILN_FUZZ_TARGETS ${_tgt})
endforeach()
add_custom_target(kiln_fuzz DEPENDS ${KILN_FUZZ_TARGETS})
message(STATUS "Kiln fuzz harnesses: ${KILN_FUZZ_TARGETS}")
