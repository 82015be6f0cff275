#!/usr/bin/env bash
# Installs what is missing, builds Release with tests and runs the default test suite (labels unit,
# stats, gpu, stress; not bench). GPU tests run on the default Vulkan device (lavapipe here) with
# the validation layer; with CI=true a missing device fails them instead of skipping.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/build.sh" release
cd "$root"
echo "test: ctest --preset release (label bench excluded)"
ctest --preset release -j1 "$@"
