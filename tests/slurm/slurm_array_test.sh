#!/bin/bash
# Slurm.JobArrayRendersOneFrame (issue 20): scripts/slurm/submit.sh on a real single-node Slurm cluster
# (tests/slurm/cluster.sh) renders one frame of the default scene as a 4-task job array plus a merge job.
#   1. The merged frame equals the single-process render of the same frame within float rounding (idiff: relative
#      1e-5, the bound of Production.CropAndSppRangePartsMergeIntoTheFullRender), for an spp split and a
#      3-band rows split; exactly one part per task.
#   2. A task cancelled mid-render (scancel) leaves no part; the merge job never runs on the rest (Slurm cancels
#      it); --merge-only writes a frame marked kiln:incomplete that names the missing range; --tasks re-renders
#      the task and the merge is then complete and equal to the single run.
#   3. A task re-queued mid-render (scontrol requeue) runs again and replaces its part: four parts merged, none
#      twice, and the frame equals the single run.
# Skips (exit 77) when the Slurm or munge programs are missing or when not root (the daemons run as root); with
# KILN_REQUIRE_SLURM=1 that is a failure. All daemons run in a private PID namespace when unshare allows it, so
# nothing outlives the test even when ctest kills it; otherwise they are stopped by the EXIT trap.
#
# Usage: slurm_array_test.sh KILN SOURCE_DIR
set -euo pipefail
kiln=$1 src=$2
export PATH="$PATH:/usr/sbin:/sbin"

skip() {
  if [ "${KILN_REQUIRE_SLURM:-0}" = 1 ]; then
    echo "FAIL (KILN_REQUIRE_SLURM=1): $*"
    exit 1
  fi
  echo "SKIP: $*"
  exit 77
}
for prog in munged mungekey munge slurmctld slurmd sbatch squeue scontrol scancel sinfo idiff iinfo; do
  command -v "$prog" > /dev/null || skip "$prog not found (bash .ci/install-deps.sh installs slurm-wlm and munge)"
done
[ "$(id -u)" = 0 ] || skip "the test cluster's daemons run as root"

if [ -z "${KILN_SLURM_NAMESPACE:-}" ] && unshare --pid --fork --kill-child --mount-proc true 2> /dev/null; then
  KILN_SLURM_NAMESPACE=1 exec unshare --pid --fork --kill-child --mount-proc bash "$0" "$@"
fi

source "$(dirname "$0")/cluster.sh"
work=$(mktemp -d "${TMPDIR:-/tmp}/kiln-slurm.XXXXXX")
chmod 755 "$work"  # munged wants every folder above its socket traversable
failed=1
cleanup() {
  slurm_cluster_stop
  if [ "$failed" = 0 ]; then
    rm -rf "$work"
  else
    echo "FAILED; logs kept in $work" >&2
    for f in "$work"/cluster/log/slurmctld.log "$work"/*/logs/*.log; do
      [ -f "$f" ] && { echo "--- $f (last lines)"; tail -n 15 "$f" | tr '\r' '\n' | tail -n 15; } >&2
    done
  fi
}
trap cleanup EXIT
t0=$SECONDS
step() { echo "[$((SECONDS - t0))s] $*"; }
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

scene="$src/scenes/default.xml"
spp=32 seed=7
# --camera and --render-arg as a user would pass them; the single run gets the same options.
submit=("$src/scripts/slurm/submit.sh" --kiln "$kiln" --spp "$spp" --seed "$seed" --cpus-per-task 1 --camera 1
  --render-arg=--max-depth=6 "$scene")

# The value printed for key by submit.sh ("key=value").
field() { sed -n "s/^$1=//p" <<< "$2"; }
meta() { iinfo -v "$1" | sed -n "s/^ *$2: \"\(.*\)\"$/\1/p"; }
same_image() {
  local out
  out=$(idiff -v -fail 1e-11 -failrelative 1e-5 -warn 1e-11 -warnrelative 1e-5 "$1" "$2") ||
    fail "$1 differs from the single run $2: $out"
  echo "  $1 matches the single run:$(grep "Max error" <<< "$out")"
}
wait_merge_completed() {
  local state
  state=$(wait_job_end 300 "$1") || fail "merge job $1 did not end"
  [ "$state" = COMPLETED ] || fail "merge job $1 ended $state"
}
log_shows() { grep -q "$2" "$1" 2> /dev/null; }

step "starting munged, slurmctld, slurmd in $work/cluster"
slurm_cluster_start "$work/cluster" || fail "the cluster did not start"

step "single-process render ($spp spp, seed $seed)"
"$kiln" render "$scene" --spp "$spp" --seed "$seed" --camera 1 --max-depth 6 -q -o "$work/single" > /dev/null
single="$work/single/default.exr"

step "case 1: 4-task spp split and 3-task rows split"
out=$("${submit[@]}" --parts 4 --dir "$work/spp")
merge_spp=$(field merge_job "$out")
out=$("${submit[@]}" --parts 3 --split rows --dir "$work/rows")
merge_rows=$(field merge_job "$out")
wait_merge_completed "$merge_spp"
wait_merge_completed "$merge_rows"
for split in spp rows; do
  n=$([ $split = spp ] && echo 4 || echo 3)
  [ "$(ls "$work/$split"/parts/task-*/default.exr | wc -l)" = "$n" ] || fail "$split: expected $n parts"
  same_image "$work/$split/default.exr" "$single"
  [ "$(meta "$work/$split/default.exr" kiln:incomplete)" = false ] || fail "$split: merged frame marked incomplete"
  [ "$(meta "$work/$split/default.exr" kiln:merged_parts)" = "$n" ] || fail "$split: not $n parts merged"
done

step "case 2: scancel task 1 mid-render"
out=$("${submit[@]}" --parts 4 --dir "$work/cancel")
array=$(field array_job "$out") merge=$(field merge_job "$out")
wait_for 240 "task 1 to start rendering" log_shows "$work/cancel/logs/task-1.log" "kiln: camera" || fail "task 1 did not start"
timeout 10 scancel "${array}_1"
state=$(wait_job_end 120 "${array}_1") || fail "task 1 did not end"
[ "$state" = CANCELLED ] || fail "task 1 ended $state, not CANCELLED (did it finish before scancel?)"
state=$(wait_job_end 240 "$merge") || fail "merge job $merge still waits after a task was cancelled"
[ "$state" = CANCELLED ] || fail "merge job ran ($state) although task 1 was cancelled"
for i in 0 2 3; do
  [ "$(wait_job_end 240 "${array}_$i")" = COMPLETED ] || fail "task $i did not complete"
done
[ -z "$(ls -A "$work/cancel/parts/task-1" 2> /dev/null)" ] || fail "the cancelled task left files: $(ls "$work/cancel/parts/task-1")"
out=$("${submit[@]}" --parts 4 --dir "$work/cancel" --merge-only)
wait_merge_completed "$(field merge_job "$out")"
[ "$(meta "$work/cancel/default.exr" kiln:incomplete)" = true ] || fail "merge without task 1 not marked incomplete"
[ "$(meta "$work/cancel/default.exr" kiln:missing)" = "0,400,0,400 8:16" ] || fail "missing range not reported in the metadata"
grep -q "missing samples 8:16 of 32 in pixels 0,400,0,400" "$work/cancel/logs/merge.log" || fail "missing range not reported in the merge log"
step "case 2: re-render task 1 with --tasks 1"
out=$("${submit[@]}" --parts 4 --dir "$work/cancel" --tasks 1)
wait_merge_completed "$(field merge_job "$out")"
[ "$(meta "$work/cancel/default.exr" kiln:incomplete)" = false ] || fail "merge after re-rendering task 1 still incomplete"
same_image "$work/cancel/default.exr" "$single"

step "case 3: scontrol requeue task 0 mid-render"
out=$("${submit[@]}" --parts 4 --dir "$work/requeue")
array=$(field array_job "$out") merge=$(field merge_job "$out")
wait_for 240 "task 0 to start rendering" log_shows "$work/requeue/logs/task-0.log" "kiln: camera" || fail "task 0 did not start"
timeout 10 scontrol requeue "${array}_0"
# Slurm holds a re-queued job back (BeginTime, about two minutes); release it now.
requeued_eligible() {
  local s
  s=$(job_state "${array}_0")
  [ "$s" = RUNNING ] || [ "$s" = COMPLETED ] || { [ "$s" = PENDING ] && timeout 10 scontrol update jobid="${array}_0" StartTime=now; }
}
wait_for 60 "the re-queued task to become eligible" requeued_eligible || fail "could not release the re-queued task"
wait_merge_completed "$merge"
[[ "$(timeout 10 scontrol show job -o "${array}_0")" =~ Restarts=([0-9]+) ]] && [ "${BASH_REMATCH[1]}" -ge 1 ] ||
  fail "task 0 was not restarted"
[ "$(grep -c "kiln: task 0 of 4" "$work/requeue/logs/task-0.log")" = 2 ] || fail "task 0 did not run twice"
grep -q "interrupted; the part was not written" "$work/requeue/logs/task-0.log" ||
  fail "the first run of task 0 was not interrupted mid-render"
[ "$(ls "$work/requeue"/parts/task-*/default.exr | wc -l)" = 4 ] || fail "expected 4 parts after the requeue"
[ "$(meta "$work/requeue/default.exr" kiln:merged_parts)" = 4 ] || fail "not 4 parts merged"
[ "$(meta "$work/requeue/default.exr" kiln:incomplete)" = false ] || fail "merged frame marked incomplete"
same_image "$work/requeue/default.exr" "$single"

step "all cases passed"
failed=0
