#!/usr/bin/env bash
# Installs what is missing, builds Release with tests and runs the default test suite (labels unit,
# stats, gpu, stress, farm; not bench or reference). GPU tests run on the default Vulkan device
# (lavapipe here) with the validation layer; with CI=true a missing device fails them instead of
# skipping. The farm test starts a one-node Slurm cluster (as root; tools/deps.sh --farm installs
# Slurm here); with CI=true it fails where it cannot, instead of skipping.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# Slurm for the farm test; where it cannot be installed (no root, no sudo) the other tests still run.
"$root/tools/deps.sh" --farm ||
  echo "test: Slurm could not be installed (tools/deps.sh --farm): the farm test skips, or fails with CI=true"
"$root/tools/build.sh" release
cd "$root"
echo "test: ctest --preset release (labels bench and reference excluded)"
ctest --preset release -j1 "$@"
