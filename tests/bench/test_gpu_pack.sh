#!/usr/bin/env bash
# CTest gpu_pack_smoke (label bench: about a minute, most of it xz): tools/gpu-pack.sh packs the
# build with one GPU test binary, the archive unpacks into a bare folder, and tools/gpu-check.sh
# run from there (no source tree, no build tree beside it) passes that binary's tests and renders
# every suite scene, with the bundled validation layer (its summary's "rounding" line comes from a
# test run under that layer).
#   tests/bench/test_gpu_pack.sh SOURCE_DIR BUILD_DIR WORKDIR
set -euo pipefail
source_dir=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work/unpacked"
"$source_dir/tools/gpu-pack.sh" --build "$build" --tests 'test_gpu_render$' "$work/pack.tar.xz"
tar -C "$work/unpacked" -xf "$work/pack.tar.xz"
cd "$work/unpacked/gpu-pack"
tools/gpu-check.sh --tests 'test_gpu_render$' --seconds 1 --size 16 --out "$work/out" >"$work/gpu-check.log" 2>&1 ||
  { tail -20 "$work/gpu-check.log"; echo "test_gpu_pack: gpu-check.sh failed in the unpacked copy" >&2; exit 1; }
grep -q '"passed": 1, "failed": 0' "$work/out/summary.json" ||
  { cat "$work/out/summary.json"; echo "test_gpu_pack: the packed test binary did not pass" >&2; exit 1; }
grep -q '"rounding": ".*: rounds ' "$work/out/summary.json" ||
  { echo "test_gpu_pack: no rounding line in the summary" >&2; exit 1; }
echo "test_gpu_pack: ok ($(du -h "$work/pack.tar.xz" | cut -f1))"
