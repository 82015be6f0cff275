#!/usr/bin/env bash
# Installs what is missing, builds Release and renders the default scene (book 3's final Cornell
# box) to cornell-book3.png in the current directory. Extra arguments go to `vkpath render`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/build.sh" release
echo "render: vkpath render $root/scenes/cornell-book3.json -o cornell-book3.png $*"
"$root/build/release/vkpath" render "$root/scenes/cornell-book3.json" -o cornell-book3.png "$@"
