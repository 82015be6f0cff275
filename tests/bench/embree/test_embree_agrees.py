#!/usr/bin/python3
"""CTest embree_agrees (docs/performance.md "The Embree reference"): the Embree reference and
vkpath render cornell-classic at 64x64 (Embree 1024 spp, vkpath 1024 spp, both `mis`-like, seed 0)
and their means over the whole image and its four halves agree per channel within 5 standard
errors (embree.compare_means: 15 comparisons; a false failure has probability < 1e-5, and both
renders are deterministic, so a build either passes or fails). It checks the reference (camera,
orientation, lights, estimator), so that its rays/s in the suite are those of the same image.
Usage: test_embree_agrees.py EMBREE_REFERENCE VKPATH SCENE WORKDIR
Exit status: 0 agree, 1 disagree or a run failed, 77 (skipped) without python3-numpy or without a
Vulkan device (vkpath exit 2)."""
import os
import subprocess
import sys

try:
    import numpy  # noqa: F401
except ImportError as e:
    print("test_embree_agrees: %s: install python3-numpy (tools/deps.sh --bench)" % e, file=sys.stderr)
    sys.exit(77)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "bench"))
import embree  # noqa: E402
import pfm  # noqa: E402

SIZE, EMBREE_SPP, VKPATH_SPP, Z_MAX = 64, 1024, 1024, 5.0


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    binary, vkpath, scene, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    wh = ["--width", SIZE, "--height", SIZE]
    ref = embree.EmbreeReference(binary)
    st = ref.render(scene, work, "embree", wh + ["--spp", EMBREE_SPP, "-o", "embree.pfm", "--variance", "embree-var.pfm"])
    cmd = [vkpath, "render", scene] + [str(a) for a in wh] + ["--spp", str(VKPATH_SPP), "--sampler", "mis", "--quiet",
                                                             "-o", os.path.join(work, "vkpath.pfm")]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode == 2:
        print("test_embree_agrees: no Vulkan device: %s" % p.stderr.strip(), file=sys.stderr)
        return 77
    if p.returncode != 0:
        print("test_embree_agrees: %s failed (%d): %s" % (" ".join(cmd), p.returncode, p.stderr.strip()), file=sys.stderr)
        return 1
    rows = embree.compare_means(pfm.read_pfm(os.path.join(work, "vkpath.pfm")), VKPATH_SPP,
                                pfm.read_pfm(os.path.join(work, "embree.pfm")),
                                pfm.read_pfm(os.path.join(work, "embree-var.pfm")), st["spp"])
    bad = [r for r in rows if not abs(r[4]) <= Z_MAX]
    print("region channel vkpath embree z")
    for r in rows:
        print("%-6s %s %.6f %.6f %+.2f%s" % (r + (" FAIL" if r in bad else "",)))
    print("Embree %s, %d spp: %.4g M rays/s; rays per sample %.3f" %
          (st["embree_version"], st["spp"], st["rays_per_second"] / 1e6, st["rays"] / st["samples"]))
    if bad:
        print("test_embree_agrees: %d of %d means differ by more than %g standard errors" % (len(bad), len(rows), Z_MAX))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
