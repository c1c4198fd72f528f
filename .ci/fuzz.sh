#!/usr/bin/env bash
# Fuzzes the scene loaders: builds the libFuzzer harnesses (tests/fuzz/fuzz_<loader>.cpp) with clang and
# -fsanitize=fuzzer,address,undefined into build/fuzz, then runs each for FUZZ_SECONDS on its seed corpus
# (tests/fuzz/corpus/<loader>) plus its saved findings (tests/fuzz/regressions/<loader>). Fails on any crash,
# leak, timeout, out-of-memory or sanitizer report; the offending input is left in build/fuzz/artifacts/<loader>/.
#
#   FUZZ_SECONDS=60     run time per harness
#   FUZZ_MIN_RUNS=N     fail a harness that executed fewer than N inputs (default 0: no minimum)
#   FUZZ_PARALLEL=N     harnesses run at once (default: nproc; each uses one core)
#   FUZZ_TARGETS="ply obj xml json pbrt"   subset to run
#   FUZZ_OPT_FLAGS="-O2 -g"   optimisation and debug flags of the instrumented build (the test command's short run
#                             builds with "-O1 -gline-tables-only": ~10% less compile time, file:line in reports)
#   FUZZ_CMAKE_ARGS=... extra configure arguments
#   FUZZ_BUILD=DIR      build folder (default build/fuzz)
#
# Run length: FUZZ_SECONDS=600 FUZZ_MIN_RUNS=1000000 gives every loader at least 10^6 executions. Measured, each
# harness on one core of the shared 2-core machine: OBJ 1.65 M in 600 s (2744/s, load average 4 to 6.5), XML 2.57 M,
# JSON 3.67 M and pbrt 1.58 M in 540 s, PLY 1.14 M in 60 s. The rate falls as the corpus grows to 64 KB inputs.
#
# Reproduce a finding:  build/fuzz/kiln_fuzz_<loader> build/fuzz/artifacts/<loader>/crash-...
# Minimise it:          build/fuzz/kiln_fuzz_<loader> -minimize_crash=1 -runs=20000 <crash file>
# then keep the minimised input as tests/fuzz/regressions/<loader>/<short-name> (replayed by the unit tests).
# Save generated inputs (every loader needs some in tests/fuzz/regressions/<loader>/, or the replay test fails):
#   mkdir -p /tmp/min && build/fuzz/kiln_fuzz_<loader> -merge=1 -max_len=4096 /tmp/min build/fuzz/corpus/<loader>
# distils the run's corpus to the inputs that each add coverage; copy a few dozen small ones, named gen_<hash>.
# Needs clang and libclang-rt-14-dev (bash .ci/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."

FUZZ_SECONDS=${FUZZ_SECONDS:-60}
FUZZ_MIN_RUNS=${FUZZ_MIN_RUNS:-0}
FUZZ_PARALLEL=${FUZZ_PARALLEL:-$(nproc)}
FUZZ_TARGETS=${FUZZ_TARGETS:-"ply obj xml json pbrt"}
BUILD=${FUZZ_BUILD:-build/fuzz}   # the ctest Fuzz.LoadersRunClean builds in its own binary tree
# Bounded memory and input size: a header that claims billions of elements must be rejected, not allocated.
RSS_LIMIT_MB=2048
MAX_LEN=65536
# Seconds for one input; loaders handle a 64 KB input in milliseconds, so anything slower is a hang.
INPUT_TIMEOUT=10

CXX=${CXX:-clang++}
if ! "$CXX" --version 2>/dev/null | grep -q clang; then
  echo "fuzz.sh: needs clang++ (set CXX, or run bash .ci/install-deps.sh)" >&2
  exit 1
fi

t0=$SECONDS
# shellcheck disable=SC2086  # FUZZ_CMAKE_ARGS is a list of arguments
cmake -S . -B "$BUILD" -DCMAKE_CXX_COMPILER="$CXX" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${FUZZ_OPT_FLAGS:--O2 -g} -DNDEBUG" -DKILN_FUZZ=ON \
  -DKILN_BUILD_TESTS=OFF -DKILN_BUILD_BENCHMARKS=OFF ${FUZZ_CMAKE_ARGS:-}
targets=()
for t in $FUZZ_TARGETS; do targets+=("kiln_fuzz_$t"); done
if ! cmake --build "$BUILD" -j"$(nproc)" --target "${targets[@]}"; then
  echo "fuzz.sh: build failed (is include(KilnFuzz) in the root CMakeLists.txt?)" >&2
  exit 1
fi
echo "fuzz.sh: harnesses built in $((SECONDS - t0))s"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:symbolize=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"

run_one() {
  local loader=$1
  local work="$BUILD/corpus/$loader" artifacts="$BUILD/artifacts/$loader" log="$BUILD/fuzz-$loader.log"
  mkdir -p "$work" "$artifacts"
  local seeds=("tests/fuzz/corpus/$loader")
  [ -d "tests/fuzz/regressions/$loader" ] && seeds+=("tests/fuzz/regressions/$loader")
  # The first folder collects new coverage-increasing inputs; the seed folders in the source tree stay read-only.
  "$BUILD/kiln_fuzz_$loader" -max_total_time="$FUZZ_SECONDS" -rss_limit_mb=$RSS_LIMIT_MB -max_len=$MAX_LEN \
    -timeout=$INPUT_TIMEOUT -print_final_stats=1 -artifact_prefix="$artifacts/" "$work" "${seeds[@]}" >"$log" 2>&1
}

declare -A pids=()
failed=()
wait_for() {
  local loader=$1
  if wait "${pids[$loader]}"; then
    local runs
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$BUILD/fuzz-$loader.log" | grep -o '[0-9]*$')
    echo "fuzz $loader: ok, ${runs:-0} inputs executed in ${FUZZ_SECONDS}s ($(( ${runs:-0} / FUZZ_SECONDS ))/s)"
    if [ "${runs:-0}" -lt "$FUZZ_MIN_RUNS" ]; then
      echo "fuzz $loader: FAILED -- ${runs:-0} executions, fewer than FUZZ_MIN_RUNS=$FUZZ_MIN_RUNS"
      failed+=("$loader")
    fi
  else
    echo "fuzz $loader: FAILED -- log $BUILD/fuzz-$loader.log, inputs in $BUILD/artifacts/$loader/"
    grep -E "ERROR: |SUMMARY: |runtime error|Test unit written" "$BUILD/fuzz-$loader.log" | head -20 || true
    failed+=("$loader")
  fi
  unset "pids[$loader]"
}
running=()
for loader in $FUZZ_TARGETS; do
  run_one "$loader" &
  pids[$loader]=$!
  running+=("$loader")
  if [ ${#running[@]} -ge "$FUZZ_PARALLEL" ]; then
    wait_for "${running[0]}"
    running=("${running[@]:1}")
  fi
done
for loader in "${running[@]}"; do wait_for "$loader"; done

if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz.sh: all harnesses ran ${FUZZ_SECONDS}s without findings ($((SECONDS - t0))s in all)"
