#!/usr/bin/env python3
"""Write the benchmark's dense-mesh scene: the room and light of scenes/cornell-classic.json with,
instead of its two boxes, one lumpy blob ("bunny-like": a sphere whose radius is modulated by a few
low-frequency harmonics) made of many small Lambertian triangles, standing on the floor in the middle
of the room where most camera and bounce rays meet it.

The blob is a latitude-longitude grid of NU x NV cells: two triangles per cell, one triangle per
cell in the rings at the poles (fans), so 2 * NU * (NV - 1) triangles; the default (1024 x 512) gives
1,046,528. Every triangle faces outwards (counter-clockwise seen from outside). The mesh goes into
OUTPUT-blob.glb beside OUTPUT.json, which includes it (a 1M-triangle JSON scene is 146 MB and slow
to parse; the .glb is 18 MB and loads in a fraction of a second). The output is deterministic.

Usage: gen_dense_mesh.py OUTPUT.json [--nu 1024] [--nv 512] [--width 256] [--height 256]
"""
import argparse
import array
import hashlib
import importlib.util
import json
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

# The room of cornell-classic.json (walls and light), without its boxes.
ROOM = [
    {"type": "quad", "Q": [555, 0, 0], "u": [0, 0, 555], "v": [0, 555, 0], "material": "green"},
    {"type": "quad", "Q": [0, 0, 555], "u": [0, 0, -555], "v": [0, 555, 0], "material": "red"},
    {"type": "quad", "Q": [0, 555, 0], "u": [555, 0, 0], "v": [0, 0, 555], "material": "white"},
    {"type": "quad", "Q": [0, 0, 555], "u": [555, 0, 0], "v": [0, 0, -555], "material": "white"},
    {"type": "quad", "Q": [555, 0, 555], "u": [-555, 0, 0], "v": [0, 555, 0], "material": "white"},
    {"type": "quad", "Q": [213, 554, 227], "u": [130, 0, 0], "v": [0, 0, 105], "material": "light"},
]
CENTRE = (278.0, 175.0, 300.0)
RADIUS = 150.0


def radius(theta, phi):
    """Radius of the blob in direction (theta from +y, phi around y): lumps of a few sizes."""
    return RADIUS * (1.0 + 0.12 * math.sin(3 * theta) * math.cos(2 * phi)
                     + 0.06 * math.sin(5 * phi + 1.0) * math.sin(4 * theta) ** 2
                     + 0.04 * math.cos(7 * theta + 2 * phi))


def point(theta, phi):
    r = radius(theta, phi)
    st = math.sin(theta)
    return (CENTRE[0] + r * st * math.cos(phi), CENTRE[1] + r * math.cos(theta), CENTRE[2] + r * st * math.sin(phi))


def blob_glb(path, nu, nv):
    """Writes the blob as one indexed glTF mesh (.glb, no normals: flat shading as the spec says);
    returns its triangle count. Vertices: the two poles and NV-1 rings of NU points."""
    gltf = _gltf_module()
    pos = array.array("f")
    for p in [point(0.0, 0.0), point(math.pi, 0.0)]:
        pos.extend(p)
    for j in range(1, nv):
        theta = math.pi * j / nv
        for i in range(nu):
            pos.extend(point(theta, 2 * math.pi * i / nu))
    top, bottom = 0, 1

    def ring(j, i):
        return 2 + j * nu + i % nu

    # Outward = counter-clockwise seen from outside. theta grows downwards (+y to -y), phi grows
    # from +x towards +z; for a cell with corners a=(j,i), b=(j,i+1), c=(j+1,i), d=(j+1,i+1), the
    # triangles (a, b, c) and (b, d, c) have normal (b - a) x (c - a) = phi-direction x
    # theta-direction, which points outwards.
    idx = array.array("I")
    for i in range(nu):
        idx.extend((top, ring(0, i + 1), ring(0, i)))
    for j in range(nv - 2):
        for i in range(nu):
            idx.extend((ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j, i + 1), ring(j + 1, i + 1), ring(j + 1, i)))
    for i in range(nu):
        idx.extend((bottom, ring(nv - 2, i), ring(nv - 2, i + 1)))
    if sys.byteorder != "little":
        pos.byteswap()
        idx.byteswap()
    g = gltf.Gltf()
    n = len(pos) // 3
    lo = [min(pos[k::3]) for k in range(3)]
    hi = [max(pos[k::3]) for k in range(3)]
    a_pos = g.add("accessors", {"bufferView": g.view(pos.tobytes()), "componentType": gltf.FLOAT, "type": "VEC3",
                                "count": n, "min": lo, "max": hi})
    a_idx = g.add("accessors", {"bufferView": g.view(idx.tobytes()), "componentType": gltf.UINT, "type": "SCALAR",
                                "count": len(idx)})
    g.add("meshes", {"name": "blob", "primitives": [{"attributes": {"POSITION": a_pos}, "indices": a_idx}]})
    g.doc["nodes"] = [{"name": "blob", "mesh": 0}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0]}]
    tmp = pathlib.Path(str(path) + ".tmp")
    g.write_glb(tmp)
    tmp.replace(path)
    return len(idx) // 3


def _gltf_module():
    spec = importlib.util.spec_from_file_location("gen_gltf_scenes", ROOT / "tools" / "gen_gltf_scenes.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def write_scene(path, nu, nv, width, height):
    """OUTPUT.json (room, light, camera) including OUTPUT-blob.glb (the mesh, material overridden by
    the JSON's Lambertian "blob"); the glb's SHA-256 is in the description, so that the JSON's hash
    (the benchmark's reference key) covers the mesh."""
    path = pathlib.Path(path)
    glb = path.with_name(path.stem + "-blob.glb")
    count = blob_glb(glb, nu, nv)
    digest = hashlib.sha256(glb.read_bytes()).hexdigest()
    scene = {
        "description": "Benchmark dense-mesh scene (generated by tools/bench/gen_dense_mesh.py): the room and "
                       "light of cornell-classic.json with a lumpy Lambertian blob of %d triangles "
                       "(%d x %d lat-long grid, %s sha256 %s) in the middle." % (count, nu, nv, glb.name, digest),
        "camera": {"lookfrom": [278, 278, -800], "lookat": [278, 278, 0], "vup": [0, 1, 0], "vfov": 40,
                   "width": width, "height": height, "defocus_angle": 0},
        "render": {"spp": 64, "max_depth": 50, "background": [0, 0, 0], "seed": 0},
        "materials": {
            "red": {"type": "lambertian", "albedo": [0.65, 0.05, 0.05]},
            "white": {"type": "lambertian", "albedo": [0.73, 0.73, 0.73]},
            "green": {"type": "lambertian", "albedo": [0.12, 0.45, 0.15]},
            "light": {"type": "diffuse_light", "emit": [15, 15, 15]},
            "blob": {"type": "lambertian", "albedo": [0.6, 0.55, 0.45]},
        },
        "objects": ROOM + [{"type": "gltf", "file": glb.name, "material": "blob"}],
    }
    tmp = pathlib.Path(str(path) + ".tmp")
    tmp.write_text(json.dumps(scene, indent=1) + "\n")
    tmp.replace(path)
    return count


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("output")
    ap.add_argument("--nu", type=int, default=1024)
    ap.add_argument("--nv", type=int, default=512)
    ap.add_argument("--width", type=int, default=256)
    ap.add_argument("--height", type=int, default=256)
    a = ap.parse_args()
    if a.nu < 3 or a.nv < 3:
        ap.error("--nu and --nv must be at least 3")
    n = write_scene(pathlib.Path(a.output), a.nu, a.nv, a.width, a.height)
    print("gen_dense_mesh: wrote %s (%d triangles)" % (a.output, n))


if __name__ == "__main__":
    main()
