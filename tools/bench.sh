#!/usr/bin/env bash
# Runs vkpath's benchmark suite (docs/performance.md "The benchmark suite"): time against error on six scenes, written to
# a results folder (CSV per scene, summary.md, summary.json, relmse_vs_time.png).
# Usage: tools/bench.sh [--quick] [--out DIR] [more options of tools/bench/bench.py --help]
# Installs what is missing (tools/deps.sh --bench: also python3-numpy and python3-matplotlib) and
# builds the Release vkpath (target vkpath only). With VKPATH=/path/to/vkpath it uses that binary
# and builds nothing. The full suite takes about an hour on a 2-core machine the first time (the
# references are cached in build/bench-cache), --quick a few minutes.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/deps.sh" --bench
if [ -z "${VKPATH:-}" ]; then
  cd "$root"
  echo "bench: cmake --preset release && cmake --build --preset release --target vkpath"
  cmake --preset release >/dev/null
  cmake --build --preset release --target vkpath
  VKPATH="$root/build/release/vkpath"
fi
exec /usr/bin/python3 "$root/tools/bench/bench.py" --vkpath "$VKPATH" "$@"
