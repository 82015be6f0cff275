#!/usr/bin/env bash
# Rebuilds the Blender references of vkpath's tests with Debian's Blender (tools/deps.sh --reference
# installs it): builds the scene in Blender, exports it to glTF as Blender's exporter writes it, and
# renders it with Cycles (tools/blender/lamps.py). Usage:
#   tools/blender-reference.sh DIR [SIZE SPP]     (default 64 4096; about 15 s on 2 cores)
# writes DIR/lamps.gltf, DIR/lamps.bin and DIR/cycles.exr. The committed copy is scenes/blender-lamps
# (tools/blender-reference.sh scenes/blender-lamps); the `reference` test renders a fresh one.
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
rm -f "$log"
echo "blender-reference: wrote $dir/lamps.gltf, lamps.bin, cycles.exr (Blender $(blender --version 2>/dev/null | head -1 | cut -d' ' -f2))"
