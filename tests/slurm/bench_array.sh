#!/bin/bash
# Wall time of one frame as a Slurm job array (scripts/slurm/submit.sh, N tasks + merge) against the same frame
# rendered by one process, on the test cluster of tests/slurm/cluster.sh (this machine as the only node). Runs
# are alternated; prints every run and the medians. The array's time runs from submit.sh's start to the merged
# EXR's modification time (written last, by the merge job).
#
# Usage: bench_array.sh KILN SOURCE_DIR [SCENE [RUNS [PARTS [CPUS_PER_TASK [SPP]]]]]   (SPP: the camera's by default)
set -euo pipefail
kiln=$(realpath "$1") src=$(realpath "$2")
scene=$(realpath "${3:-$src/scenes/default.xml}") runs=${4:-3} parts=${5:-4} cpus=${6:-1}
spp_args=()
[ -z "${7:-}" ] || spp_args=(--spp "$7")
export PATH="$PATH:/usr/sbin:/sbin"
if [ -z "${KILN_SLURM_NAMESPACE:-}" ] && unshare --pid --fork --kill-child --mount-proc true 2> /dev/null; then
  KILN_SLURM_NAMESPACE=1 exec unshare --pid --fork --kill-child --mount-proc bash "$0" "$@"
fi
source "$(dirname "$0")/cluster.sh"
work=$(mktemp -d "${TMPDIR:-/tmp}/kiln-slurm-bench.XXXXXX")
chmod 755 "$work"
trap 'slurm_cluster_stop; rm -rf "$work"' EXIT
slurm_cluster_start "$work/cluster"

now() { date +%s.%N; }
sub() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a - b}'; }
# Render seconds kiln reports ("kiln: 12.34s, ..."), summed over the logs given.
render_seconds() { cat "$@" | tr '\r' '\n' | awk '/^kiln: [0-9.]+s, / {s += substr($2, 1, length($2) - 2)} END {printf "%.2f", s}'; }
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
singles=() arrays=() tasks=() merges=()
for r in $(seq "$runs"); do
  t0=$(now)
  "$kiln" render "$scene" --seed 0 "${spp_args[@]}" -o "$work/single$r" > /dev/null 2> "$work/single$r.log"
  t1=$(now)
  singles+=("$(sub "$t1" "$t0")")
  single_render=$(render_seconds "$work/single$r.log")

  t0=$(now)
  out=$("$src/scripts/slurm/submit.sh" --kiln "$kiln" --seed 0 "${spp_args[@]}" --parts "$parts" --cpus-per-task "$cpus" --dir "$work/array$r" "$scene")
  merge=$(sed -n 's/^merge_job=//p' <<< "$out") output=$(sed -n 's/^output=//p' <<< "$out")
  state=$(wait_job_end 3600 "$merge")
  [ "$state" = COMPLETED ] || { echo "merge job $merge ended $state" >&2; exit 1; }
  arrays+=("$(sub "$(stat -c %.9Y "$output")" "$t0")")
  # Render seconds of the tasks as kiln reports them, summed.
  tasks+=("$(render_seconds "$work/array$r"/logs/task-*.log)")
  merges+=("$(sed -n 's/.*RunTime=\([0-9:]*\).*/\1/p' <<< "$(scontrol show job -o "$merge")")")
  echo "run $r: single process ${singles[-1]} s (rendering $single_render s); $parts-task array ${arrays[-1]} s (rendering, summed over the tasks, ${tasks[-1]} s; merge job ${merges[-1]})"
done
echo "median of $runs: single process $(median "${singles[@]}") s, $parts-task array $(median "${arrays[@]}") s"
