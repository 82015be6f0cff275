#!/usr/bin/env bash
# Fuzzes vkpath's input readers with libFuzzer (clang, ASan + UBSan): the JSON scene loader, the
# glTF loader and the image decoders (tests/fuzz). Each target runs SECONDS (default 60) from its
# seed corpus (tests/fuzz/corpus/<target>, read only); what it learns goes to build/fuzz/corpus-<target>,
# a crashing input to build/fuzz/artifacts/. Exits 1 if any target found a defect: copy the input
# into tests/fuzz/corpus/<target>/ with the fix, so the default test run replays it from then on.
# Usage: tools/fuzz.sh [SECONDS] [TARGET...]     (targets: scene_json gltf image)
# Installs clang and libfuzzer-14-dev (tools/deps.sh --fuzz) if they are missing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_json gltf image)
"$root/tools/deps.sh" --fuzz
cd "$root"
echo "fuzz: cmake --preset fuzz && cmake --build --preset fuzz"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz
mkdir -p build/fuzz/artifacts
status=0
for t in "${targets[@]}"; do
  mkdir -p "build/fuzz/corpus-$t"
  echo "fuzz: $t for $seconds s"
  # -rss_limit_mb: a reader that grows without bound is a finding; -timeout: so is one that hangs.
  if ! ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
       "build/fuzz/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 -max_len=65536 \
       -artifact_prefix="build/fuzz/artifacts/$t-" -print_final_stats=1 \
       "build/fuzz/corpus-$t" "tests/fuzz/corpus/$t" 2>"build/fuzz/$t.log"; then
    echo "fuzz: $t FOUND A DEFECT: build/fuzz/$t.log, input in build/fuzz/artifacts/" >&2
    tail -30 "build/fuzz/$t.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_runs|stat::peak_rss_mb|cov:" "build/fuzz/$t.log" | tail -3
  fi
done
exit $status
