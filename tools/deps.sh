#!/usr/bin/env bash
# Installs the Debian 12 packages vkpath needs to build, test and run, if any is missing.
# With --bench also python3-numpy, python3-matplotlib (for tools/bench.sh), valgrind
# (tools/instructions-per-sample.sh), xz-utils (tools/gpu-pack.sh) and libembree-dev (Embree 3: the suite's reference tracer,
# tests/bench/embree_reference); with --reference also Blender (the `reference` tests, the suite's `cycles` part); with
# --farm also Slurm and munge (the `farm` test); with --fuzz also clang and libFuzzer (tools/fuzz.sh).
# Options combine.
# Idempotent: does nothing (and needs no network) when everything is already installed.
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools
  libglm-dev libstb-dev nlohmann-json3-dev libtinyexr-dev libtinygltf-dev libgtest-dev
  libdraco-dev libmeshoptimizer-dev
  openimageio-tools  # oiiotool: the GPU tests read vkpath's EXR layers with the OpenEXR library too
  python3  # the build's dense-mesh scene (bench_scenes) and the gpu-check.sh smoke test
)
for option in "$@"; do
  case "$option" in
    # --bench: also what the benchmark suite needs (tools/bench.sh), not the tests; libembree-dev
    # (Embree 3.13 on Debian 12) for the suite's Embree reference tracer (docs/performance.md).
    --bench) packages+=(python3-numpy python3-matplotlib valgrind xz-utils libembree-dev) ;;
    # --reference: Blender (Cycles) for the `reference` tests (tools/blender-reference.sh).
    --reference) packages+=(blender) ;;
    # --farm: Slurm and munge for the `farm` test's one-node cluster (tools/slurm/cluster-up.sh).
    --farm) packages+=(slurmctld slurmd slurm-client munge) ;;
    # --fuzz: clang and libFuzzer for tools/fuzz.sh (the fuzz targets of tests/fuzz).
    --fuzz) packages+=(clang libfuzzer-14-dev) ;;
    *) echo "deps: unknown option '$option' (--bench, --reference, --farm, --fuzz)" >&2; exit 1 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "deps: installing ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends "${missing[@]}"
