#!/usr/bin/env bash
# Counts the CPU instructions one path sample costs on lavapipe, with valgrind's callgrind: a
# deterministic stand-in for rays/s where the machine's speed drifts by more than the effect to be
# measured (docs/performance.md, "Before and after the structure refactor"). Renders SCENE at
# WxH twice, with A and B samples per pixel, after a warm-up render that fills Mesa's shader cache
# (so neither counted run compiles the kernel), and prints
#   (instructions(B) - instructions(A)) / (W * H * (B - A))
# i.e. the kernel's instructions per sample, start-up and compilation cancelled out. The counts
# include every thread (LP_NUM_THREADS=1: one rasteriser thread). That total varies by 1-4 % from
# run to run (lavapipe's runtime and the host's waits), so the line also gives the instructions of
# the JIT's code alone (callgrind's functions without an object file: the kernels lavapipe compiled),
# which repeat to within about 1 % (docs/performance.md): compare builds by that figure. Usage:
#   tools/instructions-per-sample.sh VKPATH SCENE [render options...]
# Environment: W, H (default 64, 36), A, B (default 8, 72). Needs valgrind (tools/deps.sh --bench installs it).
set -euo pipefail
vkpath=$1
scene=$2
shift 2
extra=("$@")
w=${W:-64}
h=${H:-36}
a=${A:-8}
b=${B:-72}
command -v valgrind >/dev/null || { echo "instructions-per-sample: valgrind is missing (apt-get install valgrind)" >&2; exit 2; }
command -v callgrind_annotate >/dev/null || { echo "instructions-per-sample: callgrind_annotate is missing (apt-get install valgrind)" >&2; exit 2; }
# vkpath re-executes itself for huge pages (host/core/huge_pages.h), which would leave valgrind
# (it does not follow exec here): naming the tunable stops that, and keeps 4 KiB pages.
export GLIBC_TUNABLES=${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # run SPP LOG
    LP_NUM_THREADS=1 valgrind --tool=callgrind --smc-check=all-non-file --callgrind-out-file="$tmp/cg.out" \
        "$vkpath" render "$scene" --quiet --width "$w" --height "$h" --spp "$1" -o "$tmp/img.pfm" "${extra[@]}" \
        >"$2" 2>&1 || { echo "instructions-per-sample: the render failed: $(tail -3 "$2")" >&2; exit 1; }
    local total jit
    total=$(grep -o 'Collected : [0-9]*' "$2" | grep -o '[0-9]*$')
    # Instructions in code without an object file: lavapipe's JIT (callgrind_annotate's "[???]" rows).
    jit=$(callgrind_annotate --threshold=100 "$tmp/cg.out" 2>/dev/null |
        awk '/\[\?\?\?\]$/ { gsub(",", "", $1); s += $1 } END { printf "%d", s }')
    echo "$total $jit"
}
# Warm-up under valgrind too: the CPU it presents is part of Mesa's shader-cache key.
LP_NUM_THREADS=1 valgrind --tool=none --smc-check=all-non-file "$vkpath" render "$scene" --quiet --width "$w" \
    --height "$h" --spp 1 -o "$tmp/img.pfm" "${extra[@]}" >/dev/null 2>&1
ra=$(run "$a" "$tmp/a.log")
rb=$(run "$b" "$tmp/b.log")
read -r ia ja <<<"$ra"
read -r ib jb <<<"$rb"
n=$((w * h * (b - a)))
echo "$scene ${extra[*]} : $(( (ib - ia) / n )) instructions per sample ($ia at $a spp, $ib at $b spp); JIT code alone: $(( (jb - ja) / n ))"
