#!/usr/bin/env bash
# Renders a scene on a Slurm cluster: a job array of N shards, each rendering its range of the
# samples into a partial file, then a merge job that writes the image; waits for both and exits
# with the merge job's status (docs/farm.md).
#
#   tools/slurm/render.sh SCENE --shards N --spp S -o OUT [-o OUT2 ...] [options] [-- vkpath render options]
#
#   --shards N          number of array elements (1 <= N <= S); shard i renders samples
#                       [i*S/N, (i+1)*S/N) of every pixel (vkpath render --sample-range)
#   --spp S             samples per pixel of the merged image
#   -o OUT              output image (any format of vkpath's -o), repeatable
#   --work-dir DIR      partial files and job logs (default: OUT.farm beside the first OUT); must
#                       not exist or be empty, and every node must reach it. Removed after a
#                       successful merge, kept (and named) on failure
#   --cpus-per-task C   CPUs of each shard, and lavapipe's threads (LP_NUM_THREADS) (default 1)
#   --vkpath BIN        the vkpath binary, at the same path on every node (default: vkpath on
#                       PATH, else this repository's build/release/vkpath)
#   --sbatch OPTION     an option for sbatch, for every job, repeatable (e.g. --sbatch
#                       --partition=render --sbatch --time=1:00:00)
#   --job-name NAME     the jobs' name (default vkpath)
#   --exposure EV       exposure in stops of PNG outputs (the merge's --exposure; default 0)
#   -- ...              everything after -- goes to every shard's `vkpath render` (not -o, --spp,
#                       --sample-range, --partial: this script sets those; not --time)
#
# Exit status: the merge job's; 1 for bad arguments or when a shard failed (the merge job then
# never runs); 130 when interrupted (the jobs are cancelled). Needs sbatch, and SLURM_CONF or a
# configured /etc/slurm for it.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
die() { echo "render: $*" >&2; exit 1; }
usage_hint="usage: tools/slurm/render.sh SCENE --shards N --spp S -o OUT [options] [-- vkpath options] (--help)"

scene='' shards='' spp='' work='' cpus=1 vkpath='' name=vkpath exposure=0
outputs=() sbatch_options=() extra=()
need() { [ "$1" -ge 2 ] || die "$2 needs a value ($usage_hint)"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --shards) need $# "$1"; shards=$2; shift 2 ;;
    --spp) need $# "$1"; spp=$2; shift 2 ;;
    -o) need $# "$1"; outputs+=("$2"); shift 2 ;;
    --work-dir) need $# "$1"; work=$2; shift 2 ;;
    --cpus-per-task) need $# "$1"; cpus=$2; shift 2 ;;
    --vkpath) need $# "$1"; vkpath=$2; shift 2 ;;
    --sbatch) need $# "$1"; sbatch_options+=("$2"); shift 2 ;;
    --job-name) need $# "$1"; name=$2; shift 2 ;;
    --exposure) need $# "$1"; exposure=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    -*) die "unknown option '$1' (vkpath's options go after --; $usage_hint)" ;;
    *) [ -z "$scene" ] || die "one scene only (got '$scene' and '$1')"; scene=$1; shift ;;
  esac
done
[ -n "$scene" ] || die "no scene ($usage_hint)"
[ -f "$scene" ] || die "$scene: no such file"
is_count() { [[ "$1" =~ ^[1-9][0-9]*$ ]]; }
is_count "${spp:-x}" || die "--spp must be a positive integer, got '${spp:-}'"
is_count "${shards:-x}" || die "--shards must be a positive integer, got '${shards:-}'"
[ "$shards" -le "$spp" ] || die "--shards $shards exceeds --spp $spp (every shard renders at least one sample)"
is_count "$cpus" || die "--cpus-per-task must be a positive integer, got '$cpus'"
[[ "$exposure" =~ ^[-+]?[0-9]*\.?[0-9]+$ ]] || die "--exposure must be a number, got '$exposure'"
[ ${#outputs[@]} -gt 0 ] || die "no output: give -o OUT ($usage_hint)"
for option in "${extra[@]}"; do
  case "$option" in
    -o|--spp|--sample-range|--sample-range=*|--partial|--partial=*)
      die "'$option' after --: render.sh sets it (use its own -o and --spp)" ;;
    --time|--time=*)
      die "'$option' after --: a shard must render its whole range (a timed one writes a short part)" ;;
  esac
done
command -v sbatch >/dev/null || die "sbatch not found: this script submits to a Slurm cluster"

# Absolute paths: the jobs run elsewhere.
absolute() { realpath -m -- "$1"; }
scene=$(absolute "$scene")
for i in "${!outputs[@]}"; do
  outputs[i]=$(absolute "${outputs[i]}")
  [ -d "$(dirname "${outputs[i]}")" ] || die "${outputs[i]}: its folder does not exist"
done
if [ -z "$vkpath" ]; then
  vkpath=$(command -v vkpath || echo "$root/build/release/vkpath")
fi
vkpath=$(absolute "$vkpath")
[ -x "$vkpath" ] || die "$vkpath: not an executable (give --vkpath BIN)"
help=$("$vkpath" --help 2>&1 || true)   # whole, not piped: grep -q would leave it SIGPIPE
grep -q -- --sample-range <<< "$help" || die "$vkpath has no --sample-range: too old for render.sh (give --vkpath BIN)"
[ -n "$work" ] || work="${outputs[0]}.farm"
work=$(absolute "$work")
if [ -e "$work" ] && { [ ! -d "$work" ] || [ -n "$(ls -A "$work")" ]; }; then
  die "$work exists and is not an empty folder (partial files of an earlier run?): remove it or give --work-dir"
fi
mkdir -p "$work"

array_id='' merge_id='' waiter=''
cancel() {
  trap - INT TERM
  [ -z "$waiter" ] || kill "$waiter" 2>/dev/null || true
  [ -n "$merge_id" ] || merge_id=$(cat "$work/merge.jobid" 2>/dev/null || true)
  # shellcheck disable=SC2086  # no id, one id or two
  [ -z "$array_id$merge_id" ] || scancel $array_id $merge_id 2>/dev/null || true
  echo "render: interrupted; cancelled jobs ${array_id:-} ${merge_id:-}; partial files kept in $work" >&2
  exit 130
}
trap cancel INT TERM

start=$(date +%s)
array_id=$(sbatch --parsable --job-name="$name" --array="0-$((shards - 1))" --cpus-per-task="$cpus" \
  --chdir="$work" --output="$work/shard-%a.log" "${sbatch_options[@]}" \
  "$here/job.sh" shard "$vkpath" "$scene" "$spp" "$shards" "$work" "${extra[@]}") ||
  { rmdir "$work" 2>/dev/null || true; die "sbatch refused the job array"; }
array_id=${array_id%%;*}
# The merge job, and the wait for it (in the background, so that a signal reaches the trap).
sbatch --parsable --wait --job-name="$name-merge" --dependency="afterok:$array_id" \
  --kill-on-invalid-dep=yes --cpus-per-task=1 --chdir="$work" --output="$work/merge.log" \
  "${sbatch_options[@]}" "$here/job.sh" merge "$vkpath" "$work" "$shards" "$exposure" "${outputs[@]}" \
  > "$work/merge.jobid" &
waiter=$!
for _ in $(seq 100); do
  [ -s "$work/merge.jobid" ] && break
  kill -0 "$waiter" 2>/dev/null || break
  sleep 0.1
done
merge_id=$(cut -d';' -f1 "$work/merge.jobid" 2>/dev/null || true)
if [ -z "$merge_id" ]; then
  wait "$waiter" 2>/dev/null || true
  scancel "$array_id" 2>/dev/null || true
  die "sbatch refused the merge job; cancelled the job array $array_id (work folder $work kept)"
fi
echo "render: $shards shards of $spp spp as job array ${array_id}, merge job ${merge_id:-?}; work folder $work" >&2
status=0
wait "$waiter" || status=$?
waiter=
trap - INT TERM
seconds=$(($(date +%s) - start))

if [ ! -e "$work/merge.log" ]; then
  # The merge job never started: a shard failed (afterok was not met) or sbatch failed.
  failed=0
  for ((i = 0; i < shards; i++)); do
    # Failed: no partial file, or one of the samples reached when it was stopped (vkpath writes
    # that on SIGTERM, "stopped at sample"), or Slurm cancelled it.
    if [ -s "$work/shard-$i.exr" ] &&
       ! grep -q -E 'CANCELLED|stopped at sample|error' "$work/shard-$i.log" 2>/dev/null; then
      continue
    fi
    failed=$((failed + 1))
    echo "render: shard $i failed; the end of $work/shard-$i.log:" >&2
    tail -n 5 "$work/shard-$i.log" 2>/dev/null | sed 's/^/  /' >&2 || echo "  (no log: it never ran)" >&2
  done
  if [ "$failed" -eq 0 ]; then
    echo "render: the merge job never ran although every shard seems to have succeeded (was it cancelled? see $work/shard-*.log)" >&2
  else
    echo "render: the merge job did not run: $failed of $shards shards failed" >&2
  fi
  echo "render: partial files and logs kept in $work" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "render: the merge job failed (exit $status); the end of $work/merge.log:" >&2
  tail -n 5 "$work/merge.log" | sed 's/^/  /' >&2
  echo "render: partial files and logs kept in $work" >&2
  exit "$status"
fi
for out in "${outputs[@]}"; do
  [ -s "$out" ] || die "the merge job succeeded but $out is missing; partial files kept in $work"
done
for ((i = 0; i < shards; i++)); do rm -f "$work/shard-$i.exr" "$work/shard-$i.log"; done
rm -f "$work/merge.log" "$work/merge.jobid"
rmdir "$work" 2>/dev/null || echo "render: $work holds other files; left in place" >&2
echo "render: merged $shards shards ($spp spp) into ${outputs[*]} in $seconds s" >&2
