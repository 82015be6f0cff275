#!/usr/bin/env bash
# Runs vkpath's benchmark suite (docs/performance.md "The benchmark suite"): time against error on six scenes, written to
# a results folder (CSV per scene, summary.md, summary.json, relmse_vs_time.png).
# Usage: tools/bench.sh [--quick] [--out DIR] [more options of tools/bench/bench.py --help]
# Installs what is missing (tools/deps.sh --bench: also python3-numpy and python3-matplotlib) and
# builds the Release vkpath (target vkpath only) and, where Embree 3 is installed (libembree-dev,
# also from deps.sh --bench), the Embree reference (tests/bench/embree_reference) for the suite's
# "ratio to Embree". With VKPATH=/path/to/vkpath it uses that binary and builds nothing (bench.py
# then uses build/release/tests/bench/embree_reference if it exists; --embree PATH, --no-embree). The full suite takes about an hour on a 2-core machine the first time (the
# references are cached in build/bench-cache), --quick a few minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/deps.sh" --bench
if [ -z "${VKPATH:-}" ]; then
  cd "$root"
  targets=vkpath
  # The configure step says whether it found Embree (tests/bench/CMakeLists.txt).
  configured=$(cmake --preset release)
  case "$configured" in *"building embree_reference"*) targets="vkpath embree_reference" ;; esac
  echo "bench: cmake --preset release && cmake --build --preset release --target $targets"
  cmake --build --preset release --target $targets
  VKPATH="$root/build/release/vkpath"
fi
exec /usr/bin/python3 "$root/tools/bench/bench.py" --vkpath "$VKPATH" "$@"
