#!/usr/bin/env python3
"""Writes scenes/env/sky.hdr: a small equirectangular sky for the environment-lit scene.

48 x 24 texels (flat Radiance RGBE, 4.6 KB): a blue sky brightening towards the horizon, a dim
brown ground below the horizon, and a one-texel sun (~0.011 sr, ~90% of the irradiance on an
upward-facing surface). The mapping is vkpath's (shaders/shared/environment_map.h): row 0 is +y,
theta = pi v; column u = 0.5 is -z, u = 0.75 is +x. Deterministic (no randomness).

Usage: tools/gen_env_sky.py [output path]   (default: scenes/env/sky.hdr beside this script)
"""
import math
import os
import struct
import sys

W, H = 48, 24
SUN_TEXEL = (31, 5)          # column, row: u ~ 0.66 (between -z and +x), theta ~ 41 degrees
SUN_RADIANCE = (2400.0, 2200.0, 1900.0)


def radiance(i, j):
    if (i, j) == SUN_TEXEL:
        return SUN_RADIANCE
    theta = math.pi * (j + 0.5) / H
    if theta < math.pi / 2:
        t = math.cos(theta)  # 1 at the zenith, 0 at the horizon
        return (0.25 + 0.35 * (1 - t), 0.45 + 0.3 * (1 - t), 0.9 + 0.1 * (1 - t))
    return (0.12, 0.1, 0.08)


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes((0, 0, 0, 0))
    m, e = math.frexp(v)
    s = m * 256.0 / v
    return bytes((int(r * s), int(g * s), int(b * s), e + 128))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "env", "sky.hdr")
    data = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + ("-Y %d +X %d\n" % (H, W)).encode())
    for j in range(H):
        for i in range(W):
            data += rgbe(*radiance(i, j))
    with open(out, "wb") as f:
        f.write(data)


if __name__ == "__main__":
    main()
