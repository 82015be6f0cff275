#!/usr/bin/env bash
# Renders every shipped scene with every sampler at a small size and a fixed seed and prints one
# line per render: the SHA-256 of the linear PFM image, then what was rendered. Two builds that
# print the same lines render bit-identically (docs/accuracy.md, "Refactoring without changing
# an image"). Usage:
#   tools/render-digests.sh [VKPATH] > digests.txt      (default VKPATH: build/release/vkpath)
#   diff before.txt after.txt
# Environment: SIZE (default 24), SPP (default 4). A render that fails prints FAILED and its exit code.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
vkpath=${1:-$root/build/release/vkpath}
size=${SIZE:-24}
spp=${SPP:-4}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

render() {  # render LABEL SCENE ARGS...
  local label=$1 scene=$2
  shift 2
  if "$vkpath" render "$scene" --quiet --width "$size" --height "$size" --spp "$spp" -o "$out/img.pfm" "$@" \
       >/dev/null 2>"$out/err"; then
    echo "$(sha256sum <"$out/img.pfm" | cut -c1-16) $label"
  else
    echo "FAILED($?) $label: $(head -c 200 "$out/err")"
  fi
  rm -f "$out/img.pfm"
}

cd "$root"
for scene in scenes/*.json scenes/gltf/*.gltf scenes/gltf/*.glb scenes/gltf/*.json scenes/stress/*.json \
             scenes/blender-cornell-classic/*.gltf; do
  [ -f "$scene" ] || continue
  for sampler in mis light mixture bsdf; do
    render "$scene $sampler" "$scene" --sampler "$sampler"
  done
done
# The options that change the kernel's arithmetic, on scenes that exercise them.
for scene in scenes/cornell-classic.json scenes/env-sky.json scenes/gltf/materials.gltf; do
  render "$scene random" "$scene" --sequence random
  render "$scene area" "$scene" --light-sampling area
  render "$scene solid-angle" "$scene" --light-sampling solid-angle
  render "$scene uniform-pick" "$scene" --light-pick uniform
  render "$scene full-variant" "$scene" --variant full
  render "$scene adaptive" "$scene" --adaptive 0.05 --adaptive-min-spp 8 --spp 24
done
