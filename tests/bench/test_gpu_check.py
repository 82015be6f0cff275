#!/usr/bin/python3
"""CTest gpu_check_smoke: runs tools/gpu-check.sh (the script for a machine with a real GPU, issue 18)
end to end on whatever device this machine has (lavapipe in CI), without its test part and with
tiny renders, and checks its summary: exit status 0, "ok": true, the device named, how it rounds
(the rounding probe of tests/gpu/device_rounding.h), and one entry
per benchmark-suite scene, the generated dense mesh included (the bench_scenes target), each with
samples, a positive steady rays/s, a time to first sample, and no non-finite sample or cut path.
The script runs rarely and elsewhere; this keeps it from rotting unnoticed. First it checks the
build's lib/ folder (made from vkpath by tools/bundle-libs.sh): it holds every library the script
would copy for vkpath and every GPU test binary together, so the copied tests load there too, and
the validation layer (lib/layers), which the rounding probe's run in the script then loads.
Usage: test_gpu_check.py SOURCE_DIR BUILD_DIR WORKDIR
Exit status: 0 pass, 1 fail, 77 (skipped) without a Vulkan device unless CI=true."""
import json
import os
import shutil
import subprocess
import sys

SCENES = ["cornell-book3", "cornell-classic", "cornell-lights", "spheres-book1", "env-sky", "final-scene", "dense-mesh"]


def fail(msg):
    print("test_gpu_check: " + msg, file=sys.stderr)
    sys.exit(1)


def check_bundle(source, build, work):
    """build/lib holds every library that tools/bundle-libs.sh, the rule the build applies to vkpath,
    would copy for vkpath and every GPU test binary together, so the copied tests load too."""
    lib = os.path.join(build, "lib")
    gpu = os.path.join(build, "tests", "gpu")
    binaries = [os.path.join(build, "vkpath")] + sorted(
        os.path.join(gpu, f) for f in os.listdir(gpu) if f.startswith("test_") and os.access(os.path.join(gpu, f), os.X_OK))
    every = os.path.join(work, "bundle-of-every-binary")
    shutil.rmtree(every, ignore_errors=True)
    subprocess.run([os.path.join(source, "tools", "bundle-libs.sh"), every] + binaries, check=True)
    manifest = os.path.join(lib, "layers", "VkLayer_khronos_validation.json")
    if not os.path.isfile(manifest) or not os.path.isfile(os.path.join(lib, "layers", "libVkLayer_khronos_validation.so")):
        fail("%s lacks the validation layer (manifest and library) that the GPU tests need" % os.path.join(lib, "layers"))
    with open(manifest) as f:
        if json.load(f)["layer"]["library_path"] != "./libVkLayer_khronos_validation.so":
            fail("the bundled layer's manifest does not name the library beside it")
    needed = set(os.listdir(every))
    have = set(f for f in os.listdir(lib) if ".so" in f)
    if not needed:
        fail("bundle-libs.sh copies nothing for these binaries: the check checks nothing")
    if needed - have:
        fail("%s lacks %s, which the GPU test binaries load" % (lib, sorted(needed - have)))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, build, work = sys.argv[1:]
    vkpath = os.path.join(build, "vkpath")
    if subprocess.run([vkpath, "devices"], capture_output=True).returncode != 0 and os.environ.get("CI") != "true":
        print("test_gpu_check: no Vulkan device: skipped", file=sys.stderr)
        sys.exit(77)
    check_bundle(source, build, work)
    out = os.path.join(work, "gpu-check-out")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(work, exist_ok=True)
    r = subprocess.run([os.path.join(source, "tools", "gpu-check.sh"), "--build", build, "--out", out, "--no-tests",
                        "--seconds", "3", "--size", "16"], capture_output=True, text=True, timeout=600)
    print(r.stdout)
    if r.returncode != 0:
        fail("gpu-check.sh exited %d: %s" % (r.returncode, (r.stdout + r.stderr)[-2000:]))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    if s.get("ok") is not True:
        fail("summary says not ok")
    if not isinstance(s.get("device"), dict) or not s["device"].get("name"):
        fail("summary names no device: %r" % s.get("device"))
    if not isinstance(s.get("rounding"), str) or ": rounds " not in s["rounding"]:
        fail("summary says nothing of how the device rounds: %r" % s.get("rounding"))
    names = [os.path.basename(b.get("scene", "")).replace(".json", "") for b in s["bench"]]
    if sorted(names) != sorted(SCENES):
        fail("scenes %s, expected %s" % (names, SCENES))
    for b in s["bench"]:
        if "error" in b:
            fail("%s: %s" % (b["scene"], b["error"]))
        if not (b["spp"] >= 1 and b["rays_per_second_steady"] > 0 and b["seconds_to_first_sample"] > 0):
            fail("%s: implausible figures %r" % (b["scene"], b))
        if b["nonfinite_samples"] != 0 or b["loop_guard_paths"] != 0:
            fail("%s: non-finite samples or cut paths %r" % (b["scene"], b))
        if not isinstance(b.get("staging_copies"), int) or b["staging_copies"] < 0:
            fail("%s: no staging_copies count %r" % (b["scene"], b))
    print("test_gpu_check: %d scenes on %s" % (len(names), s["device"]["name"]))


if __name__ == "__main__":
    main()
