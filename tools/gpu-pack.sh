#!/usr/bin/env bash
# Packs what tools/gpu-check.sh needs into one archive, for a machine with a GPU that has no
# compiler and no package archive (docs/performance.md "On a real GPU"): tools/, scenes/,
# tests/data/, and from the build vkpath, lib/ (Debian's libraries and the validation layer, target
# bundle_libs), bench-scenes/ (the dense mesh, target bench_scenes) and the GPU test binaries,
# stripped. The binaries are nearly the same program many times over, so the archive is compressed
# with a dictionary that spans them: all 35 test binaries take ~15 MB instead of ~300 MB, and the
# whole archive 24 MB (4.5 minutes of xz on one core, 2026-12-06). On the machine (tar and xz
# unpack it):
#   tar xf gpu-pack.tar.xz && cd gpu-pack && tools/gpu-check.sh
# Usage: tools/gpu-pack.sh [--build DIR] [--tests REGEX] OUT.tar.xz
#   --build DIR    the build tree (default build/release)
#   --tests REGEX  only the test binaries whose name matches (default: every tests/gpu binary)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build/release
tests_re=.
out=""
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --tests) tests_re=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo pipefail/{/^set /!p}' "$0"; exit 0 ;;
    -*) echo "gpu-pack: unknown option $1 (--help)" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "gpu-pack: one output file, not $out and $1" >&2; exit 2; }; out=$1; shift ;;
  esac
done
[ -n "$out" ] || { echo "usage: tools/gpu-pack.sh [--build DIR] [--tests REGEX] OUT.tar.xz" >&2; exit 2; }
for need in vkpath lib/layers/VkLayer_khronos_validation.json bench-scenes/dense-mesh.json; do
  [ -e "$build/$need" ] || { echo "gpu-pack: $build/$need is missing (build the default targets first)" >&2; exit 1; }
done
command -v xz >/dev/null || { echo "gpu-pack: xz is missing (apt-get install xz-utils)" >&2; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
pack=$stage/gpu-pack
mkdir -p "$pack/build/release/tests/gpu"
cp -r "$root/tools" "$root/scenes" "$pack/"
mkdir -p "$pack/tests" && cp -r "$root/tests/data" "$pack/tests/"
strip -o "$pack/build/release/vkpath" "$build/vkpath"
cp -r "$build/lib" "$build/bench-scenes" "$pack/build/release/"
count=0
for bin in "$build"/tests/gpu/test_*; do
  [ -x "$bin" ] && [ -f "$bin" ] || continue
  [[ $(basename "$bin") =~ $tests_re ]] || continue
  strip -o "$pack/build/release/tests/gpu/$(basename "$bin")" "$bin"
  count=$((count + 1))
done
# Written beside OUT, then renamed: an interrupted run leaves no partial archive under OUT's name.
tmp=$out.tmp.$$
trap 'rm -rf "$stage" "$tmp"' EXIT
tar -C "$stage" -cf - gpu-pack | xz -T1 --lzma2=preset=6,dict=256MiB >"$tmp"
mv "$tmp" "$out"
echo "gpu-pack: wrote $out ($(du -h "$out" | cut -f1), $count test binaries)"
