#!/bin/bash
# Renders one frame of a Kiln scene on a Slurm cluster: a job array of N tasks, each rendering one part (a sample
# range of every pixel, or a band of rows) with `kiln render --spp-range` / `--crop` into its own folder, and a
# merge job that runs once every task has succeeded (--dependency=afterok) and writes the final EXR with
# `kiln merge`. The kiln binary, the scene and DIR must be visible at the same paths on the compute nodes.
#
#   scripts/slurm/submit.sh [options] SCENE [-- sbatch options for both jobs, e.g. -p render -t 2:00:00]
#
# Options:
#   --parts N          array tasks (default 4)
#   --split spp|rows   split the samples of every pixel (default) or the image rows
#   --spp N            total samples per pixel (default: the camera's)
#   --camera ID        camera to render (default: the scene's first)
#   --seed S           random seed (default 0)
#   --cpus-per-task C  CPUs per task (default: the cluster's); kiln uses them all
#   --dir DIR          job folder (default ./kiln-<scene>): DIR/parts/task-<i>/<image>.exr, DIR/logs/,
#                      and the merged frame DIR/<image>.exr
#   --kiln PATH        kiln binary (default: kiln on PATH, else this checkout's build/release/kiln)
#   --render-arg ARG   extra `kiln render` option for every part (repeatable; e.g. --render-arg=--aov=albedo)
#   --tasks LIST       run only these tasks (sbatch --array syntax, e.g. 2 or 1,3), then merge all parts again:
#                      how to re-render the parts of failed or cancelled tasks
#   --merge-only       only merge the parts already in DIR (a frame with missing parts is marked incomplete)
#
# Prints "array_job=<id>" and "merge_job=<id>". If a task fails or is cancelled, the merge job can never run
# and Slurm cancels it (--kill-on-invalid-dep=yes); resubmit the failed tasks with --tasks.
set -euo pipefail

die() {
  echo "submit.sh: $*" >&2
  exit 2
}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
scene="" kiln="" dir="" parts=4 split=spp spp="" camera="" seed=0 cpus="" tasks="" merge_only=0
render_args=() sbatch_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --*=*) opt=${1%%=*} val=${1#*=}; shift; set -- "$opt" "$val" "$@" ;;
    --parts | --split | --spp | --camera | --seed | --cpus-per-task | --dir | --kiln | --render-arg | --tasks)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --parts) parts=$2 ;;
        --split) split=$2 ;;
        --spp) spp=$2 ;;
        --camera) camera=$2 ;;
        --seed) seed=$2 ;;
        --cpus-per-task) cpus=$2 ;;
        --dir) dir=$2 ;;
        --kiln) kiln=$2 ;;
        --render-arg) render_args+=("$2") ;;
        --tasks) tasks=$2 ;;
      esac
      shift 2 ;;
    --merge-only) merge_only=1; shift ;;
    --) shift; sbatch_args=("$@"); break ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$scene" ] || die "one scene only ($scene, $1)"; scene=$1; shift ;;
  esac
done
[ -n "$scene" ] || die "no scene given (see --help)"
[ -f "$scene" ] || die "$scene: no such file"
[[ "$parts" =~ ^[1-9][0-9]*$ ]] || die "--parts: expected a positive count, got '$parts'"
[[ "$seed" =~ ^[0-9]+$ ]] || die "--seed: expected a number, got '$seed'"
[ -z "$cpus" ] || [[ "$cpus" =~ ^[1-9][0-9]*$ ]] || die "--cpus-per-task: expected a positive count, got '$cpus'"
case "$split" in spp | rows) ;; *) die "--split: expected spp or rows, got '$split'" ;; esac
if [ -z "$kiln" ]; then
  kiln=$(command -v kiln || true)
  [ -n "$kiln" ] || kiln="$here/../../build/release/kiln"
fi
[ -x "$kiln" ] || die "$kiln: not an executable kiln (use --kiln)"
command -v sbatch > /dev/null || die "sbatch not found: is this a Slurm submit host?"
kiln=$(realpath "$kiln")
scene=$(realpath "$scene")
[ -n "$dir" ] || dir="kiln-$(basename "${scene%.*}")"
dir=$(realpath -m "$dir")

# The camera's id, resolution, spp and image name, from `kiln info` ("  camera ID: PROJECTION, WxH, N spp, ... ->
# IMAGE").
info=$("$kiln" info "$scene") || die "$scene: kiln info failed"
found=0
while IFS= read -r line; do
  if [[ "$line" =~ ^\ \ camera\ ([^:]+):\ [a-z]+,\ ([0-9]+)x([0-9]+),\ ([0-9]+)\ spp,\ .*\ -\>\ (.*)$ ]]; then
    [ -z "$camera" ] || [ "${BASH_REMATCH[1]}" = "$camera" ] || continue
    camera=${BASH_REMATCH[1]} width=${BASH_REMATCH[2]} height=${BASH_REMATCH[3]} camera_spp=${BASH_REMATCH[4]}
    image=${BASH_REMATCH[5]% (Photographic tonemap)}
    found=1
    break
  fi
done <<< "$info"
[ "$found" = 1 ] || die "$scene: no camera${camera:+ with id '$camera'}"
# kiln names its output after the camera's image name (camera<ID> when it has none), always as .exr.
stem=$(basename "$image")
stem=${stem%.*}
[ -n "$stem" ] || stem="camera$camera"
[ -n "$spp" ] || spp=$((camera_spp > 0 ? camera_spp : 1))
[[ "$spp" =~ ^[1-9][0-9]*$ ]] || die "--spp: expected a positive count, got '$spp'"
[ "$split" != spp ] || [ "$parts" -le "$spp" ] || die "--parts $parts: more parts than the $spp samples per pixel"
[ "$split" != rows ] || [ "$parts" -le "$height" ] || die "--parts $parts: more parts than the $height rows"

mkdir -p "$dir/parts" "$dir/logs"
output="$dir/$stem.exr"
dependency=()
if [ "$merge_only" = 0 ]; then
  array_job=$(sbatch --parsable --array="${tasks:-0-$((parts - 1))}" --job-name="kiln-$stem" ${cpus:+--cpus-per-task=$cpus} \
    --open-mode=append --output="$dir/logs/task-%a.log" "${sbatch_args[@]}" "$here/render-part.sbatch" \
    "$kiln" "$scene" "$camera" "$spp" "$seed" "$split" "$parts" "$width" "$height" "$dir/parts" "${render_args[@]}")
  array_job=${array_job%%;*}
  echo "array_job=$array_job"
  dependency=(--dependency="afterok:$array_job" --kill-on-invalid-dep=yes)
fi
merge_job=$(sbatch --parsable --job-name="kiln-merge-$stem" --open-mode=append --output="$dir/logs/merge.log" \
  "${dependency[@]}" "${sbatch_args[@]}" "$here/merge.sbatch" "$kiln" "$dir/parts" "$stem.exr" "$output")
echo "merge_job=${merge_job%%;*}"
echo "output=$output"
