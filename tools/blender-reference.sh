#!/usr/bin/env bash
# Rebuilds the Blender references of vkpath's tests with Debian's Blender (tools/deps.sh --reference
# installs it): builds the scene in Blender, exports it to glTF as Blender's exporter writes it, and
# renders it with Cycles (tools/blender/lamps.py). Usage:
#   tools/blender-reference.sh DIR [SIZE SPP]     (default 64 4096; about 15 s on 2 cores)
# writes DIR/lamps.gltf, lamps.bin and cycles.exr (tools/blender/lamps.py), and
# DIR/vertex-colors.gltf, vertex-colors.bin and cycles-vertex-colors.exr (tools/blender/vertex_colors.py,
# 32 x 32, 1024 spp), DIR/textured.gltf, textured.bin, checker.png and cycles-textured.exr
# (tools/blender/textured.py) and DIR/clearcoat.gltf, clearcoat.bin and cycles-clearcoat.exr
# (tools/blender/clearcoat.py), both 32 x 32 at 1024 spp, and DIR/spots.gltf, spots.bin and
# cycles-spots.exr (tools/blender/spots.py, 96 x 96, 1024 spp). The committed copy is scenes/blender-reference (tools/blender-reference.sh
# scenes/blender-reference); the `reference` test renders a fresh one.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:?usage: tools/blender-reference.sh DIR [SIZE SPP]}
size=${2:-64}
spp=${3:-4096}
command -v blender >/dev/null || { echo "blender-reference: blender is not installed (tools/deps.sh --reference)" >&2; exit 2; }
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
log="$dir/blender.log"
if ! blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/lamps.py" -- \
     "$dir/lamps.gltf" "$dir/cycles.exr" "$size" "$spp" >"$log" 2>&1; then
  echo "blender-reference: Blender failed; its log: $log" >&2
  tail -5 "$log" >&2
  exit 1
fi
if ! blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/vertex_colors.py" -- \
     "$dir/vertex-colors.gltf" "$dir/cycles-vertex-colors.exr" 32 1024 >"$log" 2>&1; then
  echo "blender-reference: Blender failed; its log: $log" >&2
  tail -5 "$log" >&2
  exit 1
fi
for part in textured:32 clearcoat:32 spots:96; do
  name=${part%%:*}
  if ! blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/$name.py" -- \
       "$dir/$name.gltf" "$dir/cycles-$name.exr" "${part##*:}" 1024 >"$log" 2>&1; then
    echo "blender-reference: Blender failed; its log: $log" >&2
    tail -5 "$log" >&2
    exit 1
  fi
done
rm -f "$log"
echo "blender-reference: wrote $dir/lamps.gltf, lamps.bin, cycles.exr, vertex-colors.gltf, vertex-colors.bin, cycles-vertex-colors.exr, textured.gltf, textured.bin, checker.png, cycles-textured.exr, clearcoat.gltf, clearcoat.bin, cycles-clearcoat.exr, spots.gltf, spots.bin, cycles-spots.exr (Blender $(blender --version 2>/dev/null | head -1 | cut -d' ' -f2))"
