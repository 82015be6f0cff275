#!/usr/bin/python3
"""How much does a render change when the whole scene is moved far from the origin or scaled?
(docs/accuracy.md, "Far from the origin").

Moves a JSON scene (default scenes/cornell-classic.json) with its camera by 1e5, 1e6 and 1e7
along x, y, z and the diagonal (and, with --scales, scales it by 1e-6 ... 1e6), renders each with
the same seed as the scene at the origin, and prints per move: the relative difference of the
whole image's mean, the largest relative difference of an 8 x 8 grid of block means (blocks whose
mean is below 1% of the image mean are skipped: the black background), and the non-finite samples
the renderer dropped. Usage:
  tools/far-from-origin.py [VKPATH] [--scene S] [--size 128] [--spp 512] [--scales] [render options...]
Renders at the same seed differ only where the scene's floats differ, so a camera-relative
renderer prints zeros (to rounding) for every translation.
"""
import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "bench"))
from pfm import read_pfm  # noqa: E402  (tools/bench/pfm.py: rows top first)

ROOT = Path(__file__).resolve().parent.parent


def moved(doc, t, s):
    d = json.loads(json.dumps(doc))
    cam = d["camera"]
    for k in ("lookfrom", "lookat"):
        cam[k] = [cam[k][i] * s + t[i] for i in range(3)]
    if "focus_dist" in cam:
        cam["focus_dist"] *= s
    for o in d["objects"]:
        steps = list(o.get("transform", []))
        if s != 1.0:
            steps.append({"scale": s})
        steps.append({"translate": list(t)})
        o["transform"] = steps
    return d


def render(vkpath, scene_doc, tmp, o, extra):
    scene = Path(tmp) / "scene.json"
    scene.write_text(json.dumps(scene_doc))
    out, stats = Path(tmp) / "img.pfm", Path(tmp) / "stats.json"
    cmd = [vkpath, "render", str(scene), "--quiet", "--width", str(o.size), "--height", str(o.size), "--spp",
           str(o.spp), "--seed", "1", "-o", str(out), "--stats-json", str(stats)] + extra
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"far-from-origin: {' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    return read_pfm(out).astype(np.float64), json.loads(stats.read_text()).get("nonfinite_samples", 0)


def blocks(img, n=8):
    h, w = img.shape[:2]
    return np.array([[img[y * h // n:(y + 1) * h // n, x * w // n:(x + 1) * w // n].mean() for x in range(n)] for y in range(n)])


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("vkpath", nargs="?", default=str(ROOT / "build" / "release" / "vkpath"))
    p.add_argument("--scene", default=str(ROOT / "scenes" / "cornell-classic.json"))
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--spp", type=int, default=512)
    p.add_argument("--scales", action="store_true", help="also scale by 1e-6, 1e-5, 1e-4, 1e-3, 1e3, 1e6")
    o, extra = p.parse_known_args()
    doc = json.loads(Path(o.scene).read_text())
    moves = [(m * np.array(d), 1.0) for m in (1e5, 1e6, 1e7) for d in ((1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1))]
    if o.scales:
        moves += [(np.zeros(3), s) for s in (1e-6, 1e-5, 1e-4, 1e-3, 1e3, 1e6)]
    with tempfile.TemporaryDirectory() as tmp:
        base, _ = render(o.vkpath, doc, tmp, o, extra)
        bb = blocks(base)
        lit = bb > 0.01 * base.mean()
        print(f"{o.scene} {o.size}x{o.size} {o.spp} spp {' '.join(extra)}: image mean {base.mean():.6g}")
        print("| move | image mean rel. diff | largest block rel. diff | non-finite |")
        print("|---|---|---|---|")
        for t, s in moves:
            img, nonfinite = render(o.vkpath, moved(doc, [float(x) for x in t], s), tmp, o, extra)
            d_img = img.mean() / base.mean() - 1.0
            d_blk = np.abs(blocks(img)[lit] / bb[lit] - 1.0).max()
            label = f"scale {s:g}" if s != 1.0 else f"translate ({t[0]:g}, {t[1]:g}, {t[2]:g})"
            print(f"| {label} | {d_img:+.2e} | {d_blk:.2e} | {nonfinite} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
