#!/usr/bin/env bash
# Configures and builds vkpath with a CMake preset (default: release) into build/<preset>.
# Usage: tools/build.sh [preset]. Runs tools/deps.sh first.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
preset=${1:-release}
"$root/tools/deps.sh"
cd "$root"
echo "build: cmake --preset $preset && cmake --build --preset $preset"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
