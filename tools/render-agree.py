#!/usr/bin/python3
"""Do two vkpath builds render the same images within noise? (docs/accuracy.md, "Refactoring
without changing an image").

For renders whose digests differ (tools/render-digests.sh) because a refactor changed the order of
a floating-point sum, this renders each case with both builds for the same seeds and reports
  - the largest same-seed pixel difference |A - B|, relative to the image mean: a change of
    summation order moves a pixel by rounding (~1e-6), a change of estimator by noise (~1e-1);
  - the z-score of the difference of the two builds' image means, A with seeds 1..N against B
    with seeds 1001..1000+N (independent renders, sample variance across seeds): |z| > 4 means
    the estimators differ, whatever the rounding.
Usage: tools/render-agree.py VKPATH_A VKPATH_B CASES.txt [--size 32] [--spp 64] [--seeds 8]
CASES.txt: one case a line, 'SCENE [render options...]' (as the labels of render-digests.sh:
'scenes/env-sky.json --sampler light'); blank lines and '#' comments are skipped.
Exit status: 0 when every case agrees (|z| <= 4 and relative pixel difference <= 1e-4), 1 otherwise.
False-failure probability of the z-test per case: 6e-5 for many seeds (two-sided normal tail at
4); with 8 seeds Welch's t (about 14 degrees of freedom) gives about 1.3e-3, which is why this is a
report for a refactor's note, not a CTest.
"""
import argparse
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "bench"))
from pfm import read_pfm  # noqa: E402  (tools/bench/pfm.py: rows top first)


def render(vkpath, scene, args, size, spp, seed, out):
    cmd = [vkpath, "render", scene, "--quiet", "--width", str(size), "--height", str(size),
           "--spp", str(spp), "--seed", str(seed), "-o", str(out)] + args
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"render-agree: {' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    return read_pfm(out).astype(np.float64)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("cases")
    p.add_argument("--size", type=int, default=32)
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--seeds", type=int, default=8)
    o = p.parse_args()
    cases = []
    for line in Path(o.cases).read_text().splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            words = shlex.split(line)
            cases.append((words[0], words[1:]))
    ok = True
    print(f"| case | mean A | mean B (other seeds) | z | max same-seed abs(A-B) / mean |")
    print(f"|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene, args in cases:
            ma, mb, rel = [], [], 0.0
            for seed in range(1, o.seeds + 1):
                ia = render(o.a, scene, args, o.size, o.spp, seed, Path(tmp) / "a.pfm")
                ib = render(o.b, scene, args, o.size, o.spp, seed, Path(tmp) / "b.pfm")
                ma.append(ia.mean())
                mb.append(render(o.b, scene, args, o.size, o.spp, seed + 1000, Path(tmp) / "c.pfm").mean())
                if ia.mean() <= 0:
                    print(f"render-agree: {scene} {' '.join(args)}: black image", file=sys.stderr)
                    ok = False
                    continue
                rel = max(rel, float(np.abs(ia - ib).max() / ia.mean()))
            ma, mb = np.array(ma), np.array(mb)
            se = np.sqrt(ma.var(ddof=1) / len(ma) + mb.var(ddof=1) / len(mb))
            z = 0.0 if se == 0 else float((ma.mean() - mb.mean()) / se)
            agree = abs(z) <= 4 and rel <= 1e-4
            ok = ok and agree
            print(f"| {scene} {' '.join(args)} | {ma.mean():.6g} | {mb.mean():.6g} | {z:.2f} | {rel:.3g} |"
                  + ("" if agree else " DIFFERS"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
