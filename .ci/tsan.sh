#!/usr/bin/env bash
# ThreadSanitizer stage: builds the renderer tests with the `tsan` preset (build/tsan) and runs the tests that drive
# the TBB tile scheduler, the progressive waves, the CLI render/merge/interrupt paths and the parallel BVH build on
# 2+ threads. Fails on any TSan report, in the test process or in a `kiln` it starts, on a failing test, and when
# the TBB tasks did not actually run on more than one thread.
#
#   TSAN_FILTER=...   gtest filter (default below: about a minute of tests under TSan on 2 cores)
#   TSAN_JOBS=N       build parallelism (default: nproc)
#   KILN_REQUIRE_SHARED=ON|OFF   configure fails without ../shared and clang + libFuzzer (default ON, as in CI)
#
# Debian's libtbb and Embree are not instrumented. .ci/tsan_tbb_glue.cpp (preloaded, and named as libtbb's ITT
# collector) makes the scheduler's synchronisation visible to TSan; ignore_noninstrumented_modules=1 keeps TSan out
# of Embree's and libstdc++'s own memory traffic; .ci/tsan.supp explains why it has no entries.
# Reports (one file per process) are left in build/tsan/tsan-reports/.
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD=build/tsan
JOBS=${TSAN_JOBS:-$(nproc)}
# Two renders of one world at once, scheduler determinism, progressive waves and cancellation, CLI production paths
# (subprocesses), a parallel render into a reference film, and the BVH accelerator's parallel build + render. Excluded: the course-reference renders
# and scene sweeps (minutes under TSan, no concurrency the ones here do not have).
TSAN_FILTER=${TSAN_FILTER:-"ConcurrentRenders.*:Determinism.*:Progressive.*:Production.*:Convergence.MisBeatsUniformOnTheCornellBox:Cli.EmbreeAndBvhRendersAgree:Accels/FarOrigin.*:Scales/Scale.*"}

if [ "$(nproc)" -lt 2 ]; then
  echo "tsan.sh: needs 2+ CPUs (TBB runs one thread per CPU; races need two threads to show)" >&2
  exit 1
fi

t0=$SECONDS
mkdir -p "$BUILD"
cmake --preset tsan -DKILN_REQUIRE_SHARED="${KILN_REQUIRE_SHARED:-ON}" > "$BUILD/configure.log" 2>&1 || { cat "$BUILD/configure.log" >&2; exit 1; }
cmake --build --preset tsan -j"$JOBS" --target kiln_tests_renderer  # also builds `kiln` (the CLI tests run it)
glue="$PWD/$BUILD/libkiln_tsan_tbb_glue.so"
"${CXX:-c++}" -std=c++17 -O2 -Wall -Wextra -shared -fPIC .ci/tsan_tbb_glue.cpp -o "$glue" -ldl
t_build=$((SECONDS - t0))

reports="$PWD/$BUILD/tsan-reports"
suppressions="$PWD/.ci/tsan.supp"
rm -rf "$reports"
mkdir -p "$reports"
status=0
t1=$SECONDS
(
  cd "$BUILD/tests"
  LD_PRELOAD="$glue" INTEL_LIBITTNOTIFY64="$glue" INTEL_ITTNOTIFY_GROUPS=sync KILN_TSAN_GLUE_LOG="$reports/threads.log" \
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:ignore_noninstrumented_modules=1:suppressions=$suppressions:log_path=$reports/tsan:${TSAN_OPTIONS:-}" \
    ./kiln_tests_renderer --gtest_filter="$TSAN_FILTER" --gtest_brief=1
) || status=$?
t_run=$((SECONDS - t1))

shopt -s nullglob
found=("$reports"/tsan.*)
if [ ${#found[@]} -gt 0 ]; then
  for f in "${found[@]}"; do
    echo "=== $f"
    cat "$f"
  done
  echo "tsan.sh: ThreadSanitizer reports in ${#found[@]} process(es), see $reports/" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "tsan.sh: tests failed (exit $status)" >&2
  exit 1
fi
# The test process itself must have run TBB tasks on 2+ threads, else TSan had nothing to compare.
threads=$(awk '$2 ~ /kiln_tests_renderer$/ { print $3 }' "$reports/threads.log" 2>/dev/null | sort -n | tail -1)
if [ "${threads:-0}" -lt 2 ]; then
  echo "tsan.sh: TBB tasks ran on ${threads:-0} thread(s) in kiln_tests_renderer; the glue library was not loaded" \
       "or TBB used one thread" >&2
  exit 1
fi
echo "tsan.sh: no ThreadSanitizer reports; TBB tasks ran on $threads threads; build ${t_build}s, tests ${t_run}s"
