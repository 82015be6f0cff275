#!/usr/bin/env bash
# The farm test (label farm; tests/farm/CMakeLists.txt runs it as
# `test_farm.sh VKPATH IMAGE_DIFF SCRATCH`): starts a one-node Slurm cluster on this machine
# (tools/slurm/cluster-up.sh), renders a scene as 4 shards through tools/slurm/render.sh and
# checks that the merged image equals a single-process render of the same samples within float
# rounding (farm_image_diff: largest relative difference); then that a failing shard makes
# render.sh fail and keep its work folder. The cluster is stopped and its folder removed whatever
# happens (trap, also on SIGINT/SIGTERM; a cluster left behind by a killed run is stopped by the
# next run). SCRATCH ($VKPATH_TEST_TMP/vkpath-tests/farm when that is set) is removed after a
# pass and kept after a failure.
# Needs root and Slurm (tools/deps.sh --farm) and a Vulkan device: without them it skips (exit 77),
# or fails in CI (CI=true or CI=1), where it must run.
set -euo pipefail
[ $# -eq 3 ] || { echo "usage: test_farm.sh VKPATH IMAGE_DIFF SCRATCH" >&2; exit 1; }
root=$(cd "$(dirname "$0")/../.." && pwd)
vkpath=$1 image_diff=$2 scratch=$3
[ -z "${VKPATH_TEST_TMP:-}" ] || scratch=$VKPATH_TEST_TMP/vkpath-tests/farm
scene=$root/scenes/cornell-book3.json
size=(--width 64 --height 64)
spp=18      # 4 shards of uneven ranges: 0:4 4:9 9:13 13:18
shards=4
# The merged image adds up the same samples in other groups. The partial files carry compensated
# sums, so here the two are bit-identical (largest relative difference measured 0, docs/farm.md);
# the tolerance leaves room for float rounding elsewhere, while a missing shard is off by tens of
# per cent (0.97 for 30 of 64 spp).
tolerance=1e-5

unset SLURM_CONF   # never a real cluster's: only the one this test starts
fail() { echo "FAIL: $*"; exit 1; }
cannot_run() {
  if [ "${CI:-}" = true ] || [ "${CI:-}" = 1 ]; then
    fail "$* (CI=$CI: the farm test must run in CI)"
  fi
  echo "SKIP: $*"
  exit 77
}
[ "$(id -u)" -eq 0 ] || cannot_run "needs root to start Slurm's daemons"
for tool in slurmctld slurmd sbatch munged; do
  command -v "$tool" >/dev/null || cannot_run "Slurm is not installed ($tool missing; tools/deps.sh --farm installs it)"
done
help=$("$vkpath" --help 2>&1 || true)   # whole, not piped: grep -q would leave it SIGPIPE
grep -q -- --sample-range <<< "$help" || fail "$vkpath has no --sample-range"
grep -q -- 'vkpath merge' <<< "$help" || fail "$vkpath has no merge command"

# A cluster of an earlier run that was killed before its trap could stop it.
if [ -s "$scratch/cluster-dir" ]; then
  echo "stopping the cluster an earlier run left in $(cat "$scratch/cluster-dir")"
  "$root/tools/slurm/cluster-down.sh" "$(cat "$scratch/cluster-dir")" || true
fi
rm -rf "$scratch"
mkdir -p "$scratch"

cluster=''
cleanup() {
  local rc=$?
  trap - EXIT INT TERM HUP
  if [ -n "$cluster" ]; then
    if [ "$rc" -ne 0 ]; then
      for log in "$cluster"/log/slurmctld.log "$cluster"/log/slurmd.log; do
        [ -s "$log" ] && { echo "--- end of $log"; tail -n 10 "$log"; }
      done
    fi
    "$root/tools/slurm/cluster-down.sh" "$cluster" 2>&1 || rc=1
    rm -f "$scratch/cluster-dir"
  fi
  if [ "$rc" -eq 0 ]; then rm -rf "$scratch"; else echo "test files kept in $scratch"; fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP

seconds() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(seconds)" 'BEGIN { printf "%.1f", b - a }'; }
test_start=$(seconds)

# The single-process render, before the cluster: no device is a skip (exit 2), not a failure.
t=$(seconds)
rc=0
"$vkpath" render "$scene" "${size[@]}" --spp "$spp" --validate --quiet -o "$scratch/single.exr" || rc=$?
[ "$rc" -ne 2 ] || cannot_run "no usable Vulkan device (vkpath exit 2)"
[ "$rc" -eq 0 ] || fail "the single-process render failed (exit $rc)"
single_s=$(elapsed "$t")

# The cluster: a private folder (short: munge's socket lives there), one CPU per shard.
cluster=$(mktemp -d "${TMPDIR:-/tmp}/vkpath-farm.XXXXXX")
echo "$cluster" > "$scratch/cluster-dir"
t=$(seconds)
environment=$("$root/tools/slurm/cluster-up.sh" "$cluster") || fail "the cluster did not start"
eval "$environment"
[ "${SLURM_CONF:-}" = "$cluster/slurm.conf" ] || fail "cluster-up.sh printed no SLURM_CONF of $cluster"
cluster_s=$(elapsed "$t")

# 4 shards through render.sh, merged into an EXR and a PNG.
t=$(seconds)
"$root/tools/slurm/render.sh" "$scene" --shards "$shards" --spp "$spp" --vkpath "$vkpath" \
  -o "$scratch/merged.exr" -o "$scratch/merged.png" -- "${size[@]}" --validate ||
  fail "render.sh failed (exit $?)"
farm_s=$(elapsed "$t")
for out in merged.exr merged.png; do [ -s "$scratch/$out" ] || fail "render.sh wrote no $out"; done
[ ! -e "$scratch/merged.exr.farm" ] || fail "render.sh left its work folder $scratch/merged.exr.farm after a merge"
"$image_diff" "$scratch/single.exr" "$scratch/merged.exr" --min-value 1e-4 --max-relative "$tolerance" ||
  fail "the merged image is not the single-process render (tolerance $tolerance)"

# A failing shard (an option vkpath refuses): render.sh fails and keeps the shards' logs.
rc=0
"$root/tools/slurm/render.sh" "$scene" --shards 2 --spp 2 --vkpath "$vkpath" -o "$scratch/broken.exr" \
  -- "${size[@]}" --no-such-option > "$scratch/broken.out" 2>&1 || rc=$?
sed 's/^/  render.sh: /' "$scratch/broken.out"
[ "$rc" -ne 0 ] || fail "render.sh exited 0 although its shards failed"
[ ! -e "$scratch/broken.exr" ] || fail "render.sh wrote broken.exr although its shards failed"
[ -s "$scratch/broken.exr.farm/shard-0.log" ] || fail "render.sh did not keep the failed shards' logs"
grep -q "kept in $scratch/broken.exr.farm" "$scratch/broken.out" || fail "render.sh did not say where it kept the files"

echo "PASS: $shards shards of $spp spp merged; single render ${single_s} s, cluster up ${cluster_s} s," \
  "render.sh ${farm_s} s, whole test $(elapsed "$test_start") s"
