#!/usr/bin/env bash
# The check to run on a machine with a real GPU (issue 18): the GPU tests of a build made on
# another machine and copied over, then a short benchmark of every scene of the benchmark suite,
# summed up in one JSON file. Needs nothing but bash, coreutils, the C and C++ runtimes (glibc 2.34,
# libstdc++ with GLIBCXX_3.4.29) and the Vulkan loader with a driver: no compiler, no CMake, no
# network, no package archive (the machine may have none).
#
#   tools/gpu-check.sh [--build DIR] [--out DIR] [--seconds S] [--size N] [--tests REGEX]
#                      [--no-tests] [--no-bench] [--device SEL]
#
#   --build DIR    the build tree (default build/release): DIR/vkpath and DIR/tests/gpu/test_*
#   --out DIR      where the logs, renders and summary.json go (default gpu-check-out)
#   --seconds S    render time per suite scene (default 20), after a 1-spp warm-up render that
#                  fills the shader cache; --size N renders N x N (default 256)
#   --tests REGEX  only the test binaries whose name matches (default: every tests/gpu binary)
#   --device SEL   passed to vkpath (index or name substring; default: the most capable device)
#
# The build puts the suite's dense mesh (generated with Python) into build/release/bench-scenes and
# the shared libraries vkpath needs beyond the C and C++ runtimes into build/release/lib (this
# script puts them on LD_LIBRARY_PATH: the machine may lack Debian's packages), and lib/layers the
# validation layer that the GPU tests need (VK_LAYER_PATH). tools/gpu-pack.sh packs all of that
# into one archive (24 MB); unpack it on the machine and run this from its root. Or copy the
# repository with its build tree (tools/, scenes/, build/release/) to the machine, keeping their
# places relative to each other, and run this from the copy's root. The tests find the
# scenes and the vkpath binary through VKPATH_SOURCE_DIR and VKPATH_BINARY (tests/support/
# test_paths.h), which this script sets, so the copy may live anywhere. CI=true is set: a missing
# device or a skipped GPU test is a failure, as in CI. Every test binary and every render runs under
# a time limit, so a hung driver cannot hold the machine.
#
# summary.json: {"device": ..., "rounding": "NAME: rounds as the host (4096 probes)" or "NAME: rounds
# otherwise than the host: ..." (tests/gpu/device_rounding.h), "tests": {"binaries", "passed",
# "failed", "failures": [...], "seconds"}, "bench": [{"scene", "size", "seconds", "spp", "rays_per_second",
# "rays_per_second_steady", "seconds_to_first_sample", "seconds_longest_dispatch",
# "samples_per_dispatch", "nonfinite_samples", "pipeline_cache_bytes_loaded", "staging_copies"}, ...],
# "seconds": total}. The
# exit status is 0 only when every test binary passed and every render succeeded (the dense mesh
# missing counts as a failed render).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build/release
out=gpu-check-out
seconds=20
size=256
tests_re=.
run_tests=1
run_bench=1
device=()
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --out) out=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --tests) tests_re=$2; shift 2 ;;
    --no-tests) run_tests=0; shift ;;
    --no-bench) run_bench=0; shift ;;
    --device) device=(--device "$2"); shift 2 ;;
    -h|--help) sed -n '2,/^set -uo pipefail/{/^set /!p}' "$0"; exit 0 ;;
    *) echo "gpu-check: unknown option $1 (--help)" >&2; exit 2 ;;
  esac
done
vkpath=$build/vkpath
[ -x "$vkpath" ] || { echo "gpu-check: no vkpath binary at $vkpath (--build DIR)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
export CI=true VKPATH_SOURCE_DIR="$root" VKPATH_BINARY="$vkpath" VKPATH_TEST_TMP="$out/scratch"
# oiiotool reads the EXR layers in one CLI test: a check of the file format, which CI makes; a GPU
# machine without a package archive may lack the tool, so there that check is let go (said in the log).
export VKPATH_OIIOTOOL_OPTIONAL=1
# Debian's libraries that vkpath and the tests load, copied by the build (tools/bundle-libs.sh).
[ -d "$build/lib" ] && export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# The validation layer the GPU tests run with (and fail without), copied by the build too: this one
# rather than whatever the machine has, so that the messages are those of the layer CI runs.
if [ -f "$build/lib/layers/VkLayer_khronos_validation.json" ]; then
  export VK_LAYER_PATH="$build/lib/layers"
else
  echo "gpu-check: no validation layer in $build/lib/layers (cmake --build ... --target bundle_libs): the GPU tests use the machine's, if it has one" >&2
fi
start=$(date +%s)
device_json=""
status=0

json_str() {  # a JSON string of $1
  local s=${1//\\/\\\\}
  s=${s//\"/\\\"}
  s=${s//$'\n'/ }
  printf '"%s"' "${s//$'\t'/ }"
}
json_field() {  # the raw value of key $2 in vkpath's --stats-json file $1 (one key per line), or null
  local v
  v=$(sed -n "s/^ *\"$2\": \(.*[^,]\),\{0,1\}\$/\1/p" "$1" | head -1)
  printf '%s' "${v:-null}"
}

# ---- The device, as vkpath sees it.
"$vkpath" devices >"$out/devices.txt" 2>&1 || status=1
echo "gpu-check: devices:"
sed 's/^/  /' "$out/devices.txt"

# ---- How the test device rounds (tests/gpu/device_rounding.h): where it rounds as the host, the GPU
# tests compare kernels with their C++ twins and with each other bit for bit, elsewhere up to
# rounding; the summary's "rounding" says which (null without the test binary).
rounding=null
if [ -x "$build/tests/gpu/test_gpu_render" ]; then
  timeout 300 "$build/tests/gpu/test_gpu_render" --gtest_filter=GpuRender.CpuDevicesRoundLikeTheHost >"$out/rounding.log" 2>&1
  line=$(grep -m1 -E ': rounds (as|otherwise)' "$out/rounding.log")
  [ -n "$line" ] && rounding=$(json_str "$line")
  echo "gpu-check: ${line:-the rounding probe printed nothing (log: $out/rounding.log)}"
fi

# ---- The GPU tests: every gtest binary of tests/gpu, one after the other.
tests_json='{"skipped": true}'
if [ "$run_tests" = 1 ]; then
  t0=$(date +%s)
  passed=0 failed=0 failures=() binaries=0
  for bin in "$build"/tests/gpu/test_*; do
    [ -x "$bin" ] && [ -f "$bin" ] || continue
    name=$(basename "$bin")
    [[ $name =~ $tests_re ]] || continue
    binaries=$((binaries + 1))
    echo "gpu-check: $name"
    if timeout 900 "$bin" --gtest_brief=1 >"$out/$name.log" 2>&1; then
      passed=$((passed + 1))
    else
      failed=$((failed + 1))
      failures+=("$name: $(grep -m1 -E 'FAILED|Failure|error' "$out/$name.log" | cut -c1-200)")
      status=1
      echo "gpu-check:   FAILED (log: $out/$name.log)"
    fi
  done
  list=""
  for f in "${failures[@]+"${failures[@]}"}"; do list+="${list:+, }$(json_str "$f")"; done
  tests_json="{\"binaries\": $binaries, \"passed\": $passed, \"failed\": $failed, \"failures\": [$list], \"seconds\": $(($(date +%s) - t0))}"
fi

# ---- The suite's scenes (tools/bench/bench.py SCENES): a warm-up render, then a timed one. The
# dense mesh is generated (it needs Python), on the build machine: `cmake --build DIR --target
# bench_scenes` puts it in DIR/bench-scenes, which travels with the build; without it the check
# says so and fails.
bench_json=""
if [ "$run_bench" = 1 ]; then
  scenes=()
  for s in cornell-book3 cornell-classic cornell-lights spheres-book1 env-sky next-week/final-scene; do
    scenes+=("$root/scenes/$s.json")
  done
  dense=$build/bench-scenes/dense-mesh.json
  if [ -f "$dense" ]; then
    scenes+=("$dense")
  else
    status=1
    echo "gpu-check: $dense is missing: run 'cmake --build <build> --target bench_scenes' on the build machine"
    bench_json="{\"scene\": \"dense-mesh\", \"error\": $(json_str "not generated: cmake --build <build> --target bench_scenes on the build machine")}"
  fi
  # vkpath's kernel cache in the output folder: the warm-up render stores the specialized kernel
  # and the driver's VkPipelineCache data there, and the timed render loads them
  # (pipeline_cache_bytes_loaded > 0 where the driver keeps pipelines in it; lavapipe does not).
  export VKPATH_CACHE_DIR="$out/kernel-cache"
  for path in "${scenes[@]}"; do
    scene=${path#"$root"/}
    name=$(basename "$scene" .json)
    echo "gpu-check: $scene, ${size}x$size, $seconds s"
    common=(--width "$size" --height "$size" "${device[@]+"${device[@]}"}" --quiet)
    timeout 600 "$vkpath" render "$path" "${common[@]}" --spp 1 -o "$out/$name-warmup.pfm" >/dev/null 2>&1
    if timeout $((seconds * 3 + 300)) "$vkpath" render "$path" "${common[@]}" --spp 16777216 --time "$seconds" \
         --stats-json "$out/$name.json" -o "$out/$name.exr" >"$out/$name.log" 2>&1; then
      s=$out/$name.json
      entry="{\"scene\": $(json_str "$scene"), \"size\": \"${size}x$size\", \"seconds\": $seconds"
      for k in spp rays_per_second rays_per_second_steady seconds_to_first_sample seconds_longest_dispatch \
               samples_per_dispatch workgroup nonfinite_samples loop_guard_paths pipeline_cache_bytes_loaded \
               staging_copies; do
        entry+=", \"$k\": $(json_field "$s" "$k")"
      done
      entry+="}"
      [ "$(json_field "$s" nonfinite_samples)" = 0 ] && [ "$(json_field "$s" loop_guard_paths)" = 0 ] || status=1
      [ -z "$device_json" ] && device_json=$(sed -n '/"device": {/,/}/p' "$s" | tr -d '\n' | sed 's/^ *"device": //; s/,$//')
    else
      status=1
      entry="{\"scene\": $(json_str "$scene"), \"error\": $(json_str "$(tail -c 300 "$out/$name.log")")}"
      echo "gpu-check:   FAILED (log: $out/$name.log)"
    fi
    bench_json+="${bench_json:+,
    }$entry"
  done
fi

{
  echo "{"
  echo "  \"device\": ${device_json:-$(json_str "$(head -3 "$out/devices.txt")")},"
  echo "  \"rounding\": $rounding,"
  echo "  \"tests\": $tests_json,"
  echo "  \"bench\": ["
  [ -n "$bench_json" ] && echo "    $bench_json"
  echo "  ],"
  echo "  \"seconds\": $(($(date +%s) - start)),"
  echo "  \"ok\": $([ "$status" = 0 ] && echo true || echo false)"
  echo "}"
} >"$out/summary.json"
echo "gpu-check: wrote $out/summary.json in $(($(date +%s) - start)) s: $([ "$status" = 0 ] && echo ok || echo FAILED)"
exit "$status"
