#!/usr/bin/env python3
"""Makes scenes/next-week/earthmap.png: an invented planet in the equirectangular layout of the
book's earthmap.jpg ("Ray Tracing: The Next Week", sec. 4.5): longitude along x, the north pole at
the top. Oceans, continents and ice caps from fractal value noise on the unit sphere (no seam at
the date line, no pinching at the poles); deterministic (fixed seed), pure Python with PIL.

Usage: tools/gen_earthmap.py [OUT.png] [WIDTH]   (default scenes/next-week/earthmap.png, 512)
"""
import math
import os
import random
import sys

from PIL import Image


def lattice(seed):
    rnd = random.Random(seed)
    return [rnd.random() for _ in range(4096)]


def value_noise(table, x, y, z):
    """Trilinear value noise with smoothstep weights, in [0, 1]."""
    xi, yi, zi = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - xi, y - yi, z - zi
    sx, sy, sz = fx * fx * (3 - 2 * fx), fy * fy * (3 - 2 * fy), fz * fz * (3 - 2 * fz)

    def at(i, j, k):
        return table[((i * 73856093) ^ (j * 19349663) ^ (k * 83492791)) & 4095]

    acc = 0.0
    for dk in (0, 1):
        for dj in (0, 1):
            for di in (0, 1):
                w = (sx if di else 1 - sx) * (sy if dj else 1 - sy) * (sz if dk else 1 - sz)
                acc += w * at(xi + di, yi + dj, zi + dk)
    return acc


def fbm(table, p, octaves):
    acc, amp, norm, f = 0.0, 1.0, 0.0, 1.0
    for _ in range(octaves):
        acc += amp * value_noise(table, p[0] * f, p[1] * f, p[2] * f)
        norm += amp
        amp *= 0.5
        f *= 2.03
    return acc / norm


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "scenes", "next-week", "earthmap.png")
    width = int(sys.argv[2]) if len(sys.argv) > 2 else 512
    height = width // 2
    height_table, moisture_table = lattice(1), lattice(2)
    img = Image.new("RGB", (width, height))
    px = img.load()
    for j in range(height):
        lat = math.pi * (0.5 - (j + 0.5) / height)  # +pi/2 at the top row
        for i in range(width):
            lon = 2 * math.pi * (i + 0.5) / width
            p = (math.cos(lat) * math.cos(lon) * 2.2 + 10, math.sin(lat) * 2.2 + 10, math.cos(lat) * math.sin(lon) * 2.2 + 10)
            h = fbm(height_table, p, 6)
            m = fbm(moisture_table, p, 4)
            polar = abs(lat) / (math.pi / 2)
            if polar > 0.86 + 0.06 * (h - 0.5):
                c = (235, 240, 245)  # ice
            elif h < 0.52:
                depth = (0.52 - h) / 0.52
                c = (int(20 + 30 * (1 - depth)), int(50 + 60 * (1 - depth)), int(110 + 70 * (1 - depth)))
            else:
                e = (h - 0.52) / 0.48
                if m > 0.5 and polar < 0.7:
                    c = (int(40 + 60 * e), int(100 + 50 * e), int(40 + 30 * e))  # forest and grass
                else:
                    c = (int(150 + 60 * e), int(130 + 50 * e), int(80 + 40 * e))  # desert and rock
                if e > 0.6:
                    c = tuple(min(255, int(v + 80 * (e - 0.6))) for v in c)  # mountains
            px[i, j] = c
    img.save(out, optimize=True)
    print(f"wrote {out} ({width}x{height})")


if __name__ == "__main__":
    main()
