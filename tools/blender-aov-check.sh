#!/usr/bin/env bash
# Checks that Blender's compositor reads vkpath's feature layers (`--aov`, docs/design.md "Feature
# images") as vkpath wrote them: renders cornell-book3 small with every layer into an EXR and, for
# comparison, into PFM files, then has Debian's Blender (tools/deps.sh --reference installs it)
# route each pass of the EXR through its compositor to a file of its own and compare every value
# (tools/blender/aov_compositor.py). The `reference` test reference.blender_aov runs it. Usage:
#   tools/blender-aov-check.sh VKPATH DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
vkpath=${1:?usage: tools/blender-aov-check.sh VKPATH DIR}
dir=${2:?usage: tools/blender-aov-check.sh VKPATH DIR}
command -v blender >/dev/null || { echo "blender-aov-check: blender is not installed (tools/deps.sh --reference)" >&2; exit 2; }
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
layers=albedo,normal,depth,position,emission,variance,spp
rm -f "$dir"/f.exr "$dir"/f*.pfm "$dir"/blender-*.exr
"$vkpath" render "$root/scenes/cornell-book3.json" --width 24 --height 16 --spp 4 --aov "$layers" \
    -o "$dir/f.exr" -o "$dir/f.pfm" --quiet
log="$dir/blender-aov.log"
if ! blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/aov_compositor.py" -- \
     "$dir/f.exr" "$dir/f" "$dir" "$layers" >"$log" 2>&1; then
  echo "blender-aov-check: Blender did not read the layers as written; its log: $log" >&2
  grep -E 'aov_compositor|Error' "$log" | tail -8 >&2
  exit 1
fi
grep 'aov_compositor:' "$log"
