#!/usr/bin/python3
"""Direct light in cornell-classic's room without its boxes, against Lambert's polygon formula.

The walls of the Cornell box see its ceiling light nearly edge-on (emission angles of 75-85
degrees near the ceiling). This tool takes a SIZE x SIZE render of the empty room with direct light
only (vkpath: scenes/cornell-classic.json without its boxes, --max-depth 2; Cycles:
tools/blender/cornell_cycles.py with MAX_BOUNCES 0 and DROP_PREFIX box_) and prints, per surface,
the sum of the pixels that see that surface alone against the closed form: (rho / pi) L E(x),
E from Lambert's formula (Arvo 1995, eq. 7), averaged over each pixel's footprint with an 8 x 8 grid
(on such pixels E is smooth, so the grid is exact to ~1e-5). Pixels on an edge (the light's
included) are left out: a grid of points misjudges their coverage. docs/accuracy.md "Against
Cycles: the Cornell box's walls" has the commands and the numbers; the same check without
Blender is the test GpuAnalytic.EmptyCornellRoomWallsSeeTheLightEdgeOn.

Usage: tools/bench/room_direct.py IMAGE.pfm [IMAGE.pfm ...]   (all of one size; square)
       tools/bench/room_direct.py --write-scene room.json       (the empty room, max_depth 2)
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pfm  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
L_EMIT = 15.0
LIGHT = np.array([[213, 554, 227], [343, 554, 227], [343, 554, 332], [213, 554, 332]], float)
# name, axis, plane value, inward normal, albedo (scenes/cornell-classic.json)
SURFACES = [("red wall", 0, 0.0, (1, 0, 0), (0.65, 0.05, 0.05)),
            ("green wall", 0, 555.0, (-1, 0, 0), (0.12, 0.45, 0.15)),
            ("floor", 1, 0.0, (0, 1, 0), (0.73, 0.73, 0.73)),
            ("ceiling", 1, 555.0, (0, -1, 0), (0.73, 0.73, 0.73)),
            ("back wall", 2, 555.0, (0, 0, -1), (0.73, 0.73, 0.73))]


def write_scene(path):
    with open(os.path.join(ROOT, "scenes", "cornell-classic.json")) as f:
        scene = json.load(f)
    scene["objects"] = [o for o in scene["objects"] if o["type"] != "box"]
    scene["render"]["max_depth"] = 2
    scene["description"] = "cornell-classic.json without its boxes, direct light only (tools/bench/room_direct.py)"
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)


def polygon_irradiance(x, n):
    """E / L at points x (..., 3) with normals n (..., 3) from LIGHT, which lies above their horizon."""
    s = np.zeros(x.shape[:-1])
    for i in range(len(LIGHT)):
        a = LIGHT[i] - x
        b = LIGHT[(i + 1) % len(LIGHT)] - x
        a /= np.linalg.norm(a, axis=-1, keepdims=True)
        b /= np.linalg.norm(b, axis=-1, keepdims=True)
        c = np.cross(a, b)
        cl = np.linalg.norm(c, axis=-1)
        s += np.arctan2(cl, (a * b).sum(-1)) * (c * n).sum(-1) / np.maximum(cl, 1e-300)
    return 0.5 * np.abs(s)


def hits(size, offsets):
    """Surface index per (row, column, sub-position) of camera rays through the pixel points
    (i + ox, j + oy), offsets in [0, 1] (-1: the light or a miss), and the points."""
    eye = np.array([278.0, 278.0, -800.0])
    half = np.tan(np.radians(20.0))  # vfov 40, square image; the image's x runs along -x
    px = (np.arange(size)[:, None] + offsets[None, :]).ravel()
    X, Y = np.meshgrid(px, px)
    d = np.stack([-(X / size - 0.5) * 2 * half, (0.5 - Y / size) * 2 * half, np.ones_like(X)], axis=-1)
    t0 = -eye[2] / d[..., 2]
    e = eye + t0[..., None] * d
    inside = (e[..., 0] > 0) & (e[..., 0] < 555) & (e[..., 1] > 0) & (e[..., 1] < 555)
    with np.errstate(divide="ignore", invalid="ignore"):
        ts = np.stack([(v - eye[ax]) / d[..., ax] for _, ax, v, _, _ in SURFACES])
    ts[~(ts > t0[None])] = np.inf
    k, t = ts.argmin(0), ts.min(0)
    x = eye + t[..., None] * d
    with np.errstate(divide="ignore"):
        tl = (554.0 - eye[1]) / d[..., 1]
    xl = eye + tl[..., None] * d
    on_light = (tl > t0) & (tl < t) & (xl[..., 0] >= 213) & (xl[..., 0] <= 343) & (xl[..., 2] >= 227) & (xl[..., 2] <= 332)
    k = np.where(inside & ~on_light, k, -1)
    n = len(offsets)
    return k.reshape(size, n, size, n), x.reshape(size, n, size, n, 3)


def closed_form(size):
    """(surface per pixel, -1 where mixed; expected radiance per pixel, rgb)."""
    k_edge, _ = hits(size, np.linspace(0.0, 1.0, 10))
    pure = np.where((k_edge.min(axis=(1, 3)) == k_edge.max(axis=(1, 3))), k_edge[:, 0, :, 0], -1)
    k, x = hits(size, (np.arange(8) + 0.5) / 8)
    normals = np.array([s[3] for s in SURFACES], float)[np.maximum(k, 0)]
    e = polygon_irradiance(x, normals)
    e[(x[..., 1] >= 554.0) | (k < 0)] = 0.0  # above the light's plane: its back
    albedo = np.array([s[4] for s in SURFACES], float)[np.maximum(pure, 0)]
    return pure, albedo / np.pi * L_EMIT * e.mean(axis=(1, 3))[..., None]


def main(argv):
    if len(argv) == 3 and argv[1] == "--write-scene":
        write_scene(argv[2])
        return 0
    if len(argv) < 2 or argv[1].startswith("-"):
        print(__doc__.strip().splitlines()[-2].strip(), file=sys.stderr)
        return 2
    size = None
    for path in argv[1:]:
        img = pfm.read_pfm(path).astype(np.float64)
        if size != img.shape[0]:
            size = img.shape[0]
            if img.shape[1] != size:
                print("room_direct: %s: %dx%d is not square" % (path, img.shape[1], size), file=sys.stderr)
                return 1
            pure, expected = closed_form(size)
        print(path)
        for i, (name, _, _, _, _) in enumerate(SURFACES):
            m = pure == i
            got, want = img[m].sum(), expected[m].sum()
            rel = "%+.4f %%" % (100 * (got / want - 1)) if want > 0 else "(expected 0)"
            print("  %-10s %5d pixels: image %.6g, closed form %.6g: %s" % (name, m.sum(), got, want, rel))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
