#!/usr/bin/env python3
"""Write the small glTF 2.0 test scenes of scenes/gltf/ (scenes/README.md, "glTF"), by hand,
with the Python standard library only. Each file exercises one part of vkpath's glTF loader and
has a test in tests/unit/test_gltf_*.cpp that checks the numbers given here:

  modes.gltf + modes.bin       every triangle topology: non-indexed, u8/u16/u32 indices, strip, fan
  hierarchy.gltf               nested TRS and matrix nodes, a mirror, a zero scale, two scenes
                               (buffer as a base64 data URI)
  accessors.glb                GLB container; interleaved (strided) attributes, sparse accessors
                               (also on an accessor without bufferView), normalized integers,
                               KHR_mesh_quantization
  materials.gltf + .bin        every material parameter and extension vkpath reads, textures
  + textures/checker.png       (data URI and external PNG), samplers, KHR_texture_transform
  cameras.gltf                 orthographic and perspective cameras under a rotated parent
  no-camera.gltf               no camera: vkpath frames the scene's bounds
  emissive.glb                 emissive triangles (single- and double-sided), a PNG inside the GLB
  extensions.gltf              an extension vkpath does not implement, only used: one warning
  lights.gltf                  KHR_lights_punctual (tests/unit/test_gltf_lights.cpp): a point, a
                               spot (with range) and a directional light on translated, rotated and
                               scaled nodes, one light no node uses, over a floor of albedo 0.8
  vertex-colors.gltf           COLOR_0 (tests/gpu/test_gpu_vertex_colors.cpp): four quads whose
                               corner colours are linear in x and y, as uint16, float RGBA (alpha
                               under MASK), float RGB and uint8
  unlit.gltf                   KHR_materials_unlit (tests/gpu/test_gpu_unlit.cpp): two quads of one
                               unlit colour, one facing the camera's side, one turned away
  point-lamp.gltf              Blender's light units (tests/gpu/test_gpu_punctual.cpp): a 100 W
                               point lamp as Blender's exporter writes it, 2 m above that floor
  textures.gltf                textures on the device (tests/gpu/test_gpu_textures.cpp): a 4x4 image
                               of 16 distinct sRGB colours on quads with UVs in [-0.75, 1.75] and
                               pure Lambertian materials (specularFactor 0): nearest filtering with
                               REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT, KHR_texture_transform,
                               bilinear filtering, a metallicRoughness map, a normal map (with
                               and without NORMAL)
  alpha.gltf                   alphaMode (tests/gpu/test_gpu_alpha.cpp): MASK with a texture's
                               alpha x the factor's against the cutoff, BLEND with alpha 0.25, and
                               an opaque quad behind a fully cut-out one
  emissive-texture.gltf        an emissiveTexture (tests/gpu/test_gpu_emissive_texture.cpp): a lamp
                               quad seen straight on, and a panel of the same material over a floor
  emissive-spot.gltf           per-triangle power of a textured emitter (tests/gpu/
                               test_gpu_emissive_texture.cpp): a panel of 128 triangles under a
                               32x32 texture that is dark (sRGB 1/255) but for a bright 4x4 square,
                               over a floor
  specular-textures.gltf       KHR_materials_specular textures on the device (tests/gpu/
                               test_gpu_specular_textures.cpp, test_gltf_materials.cpp): three
                               2 x 2 quads (quad i at x in [2.5 i, 2.5 i + 2], y in [0, 2], facing
                               +z, UV (0, 0) top left to (1, 1) bottom right), base colour 0.1,
                               roughness 0.5: a specularTexture whose alpha is 0 in the left half
                               and 1 in the right (2x1, nearest, clamp), a uniform one of alpha
                               128/255 (1x1), and a specularColorTexture white in the left half and
                               sRGB (0, 128, 255) in the right
  transmission-textures.gltf   a KHR_materials_transmission transmissionTexture (tests/gpu/
                               test_gpu_transmission_texture.cpp): two quads laid out as in
                               specular-textures.gltf, base colour 0.5, transmissionFactor 1 x a
                               texture whose R is 0 in the left half and 1 in the right (2x1,
                               nearest, clamp), and x a uniform R of 128/255 (1x1)
  texcoord1.gltf               textureInfo.texCoord 1 (tests/gpu/test_gpu_texcoord1.cpp,
                               test_gltf_materials.cpp): two quads laid out as in
                               specular-textures.gltf whose TEXCOORD_0 is mirrored (u -> 1 - u) and
                               whose TEXCOORD_1 (normalized uint16) is not: a baseColorTexture and a
                               specularTexture (alpha 0 | 1), both 2x1, nearest, clamp, through
                               TEXCOORD_1
  layer-textures.gltf          KHR_materials_clearcoat and KHR_materials_sheen textures on the device
                               (tests/gpu/test_gpu_layers.cpp, test_gltf_materials.cpp): five quads
                               laid out as in specular-textures.gltf (with TANGENT +x), base colour
                               0.1, roughness 0.5: a clearcoatTexture whose R is 0 | 1, a
                               clearcoatRoughnessTexture whose G is 0 | 1, a sheenColorTexture white
                               | sRGB (0, 128, 255), a sheenRoughnessTexture whose A is 0 | 1 (all
                               2x1, nearest, clamp; the other channels are decoys), and a black base
                               under a coat whose clearcoatNormalTexture (1x1) tilts it about 21
                               degrees towards +x
  instances.gltf               instancing (tests/gpu/test_gpu_instancing.cpp, test_gltf_loader.cpp):
                               a lumpy blob with NORMALs used by 5 nodes (translated, rotated, a
                               non-uniform scale, a mirror, a mirror inside a rotated parent), a
                               glass tetrahedron used by 2 nodes (one mirrored), an emissive lamp
                               used by 2 nodes (stays flattened), a floor and a light panel

Deterministic: running it again writes byte-identical files.
Usage: tools/gen_gltf_scenes.py [output dir]   (default: scenes/gltf beside tools/)
       tools/gen_gltf_scenes.py --grid TRIANGLES OUT.glb
           a wavy height field of at least TRIANGLES triangles (indexed, uint32, POSITION + NORMAL,
           a camera and an emissive panel) for load-time and memory measurements; not committed.
       tools/gen_gltf_scenes.py --instances COUNT TRIANGLES OUT.glb
           COUNT nodes on a square grid sharing one lumpy blob of at least TRIANGLES triangles
           (POSITION + NORMAL, uint32 indices), each turned, scaled and every third one mirrored,
           on a floor under an emissive panel, with a camera: for the instancing measurements
           (docs/performance.md "Instancing"); not committed.
"""
import array
import base64
import json
import math
import pathlib
import struct
import sys
import zlib

FLOAT, BYTE, UBYTE, SHORT, USHORT, UINT = 5126, 5120, 5121, 5122, 5123, 5125
FMT = {FLOAT: "f", BYTE: "b", UBYTE: "B", SHORT: "h", USHORT: "H", UINT: "I"}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
TRIANGLES, STRIP, FAN = 4, 5, 6


def png(width, height, rgba):
    """A PNG (RGBA, 8 bits) of width x height pixels, rgba = rows of (r, g, b, a) tuples."""
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rgba)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


CHECKER_2 = png(2, 2, [[(255, 0, 0, 255), (0, 255, 0, 255)], [(0, 0, 255, 255), (255, 255, 255, 128)]])
CHECKER_4 = png(4, 4, [[(0, 128, 255, 255) if (x + y) % 2 == 0 else (255, 64, 0, 255) for x in range(4)]
                       for y in range(4)])


class Gltf:
    """A glTF document under construction, with one binary buffer."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "vkpath tools/gen_gltf_scenes.py"}}
        self.bin = bytearray()

    def add(self, key, item):
        self.doc.setdefault(key, []).append(item)
        return len(self.doc[key]) - 1

    def view(self, data, stride=None, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        if target:
            v["target"] = target
        self.bin += data
        return self.add("bufferViews", v)

    def accessor(self, values, ctype, atype, normalized=False, minmax=False, view=None, offset=0, count=None):
        """An accessor of values (flat list); its own tightly packed bufferView unless view is given."""
        n = NCOMP[atype]
        if view is None and values is not None:
            view = self.view(struct.pack("<%d%s" % (len(values), FMT[ctype]), *values))
        a = {"componentType": ctype, "type": atype, "count": count if count is not None else len(values) // n}
        if view is not None:
            a["bufferView"] = view
        if offset:
            a["byteOffset"] = offset
        if normalized:
            a["normalized"] = True
        if minmax:
            a["min"] = [min(values[i::n]) for i in range(n)]
            a["max"] = [max(values[i::n]) for i in range(n)]
        return self.add("accessors", a)

    def positions(self, pts):
        return self.accessor([c for p in pts for c in p], FLOAT, "VEC3", minmax=True)

    def image_view(self, data, mime):
        return self.add("images", {"bufferView": self.view(data), "mimeType": mime})

    def write_gltf(self, path, bin_name=None):
        """.gltf with the buffer in bin_name, or as a data URI when bin_name is None."""
        if self.bin:
            uri = bin_name or "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
            self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
            if bin_name:
                (path.parent / bin_name).write_bytes(bytes(self.bin))
        path.write_text(json.dumps(self.doc, indent=1) + "\n")

    def write_glb(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        js = json.dumps(self.doc, separators=(",", ":")).encode()
        js += b" " * (-len(js) % 4)
        body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin)
        path.write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def square(x0, y0=0.0, z=0.0):
    """The corners of the unit square at (x0, y0), counter-clockwise seen from +z."""
    return [(x0, y0, z), (x0 + 1, y0, z), (x0 + 1, y0 + 1, z), (x0, y0 + 1, z)]


def modes(out):
    g = Gltf()
    prims = []
    tri = square(0)
    prims.append({"attributes": {"POSITION": g.positions([tri[0], tri[1], tri[2], tri[0], tri[2], tri[3]])}})
    for x0, ctype in ((2, UBYTE), (4, USHORT), (6, UINT)):
        prims.append({"attributes": {"POSITION": g.positions(square(x0))},
                      "indices": g.accessor([0, 1, 2, 0, 2, 3], ctype, "SCALAR")})
    s = square(8)
    prims.append({"attributes": {"POSITION": g.positions([s[0], s[1], s[3], s[2]])}, "mode": STRIP})
    f = square(10)  # fan around the centre, closed by repeating the first corner: 4 triangles
    prims.append({"attributes": {"POSITION": g.positions([(10.5, 0.5, 0.0)] + f)},
                  "indices": g.accessor([0, 1, 2, 3, 4, 1], USHORT, "SCALAR"), "mode": FAN})
    g.add("meshes", {"name": "modes", "primitives": prims})
    g.add("nodes", {"name": "modes", "mesh": 0})
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0]}]
    g.write_gltf(out / "modes.gltf", "modes.bin")


def hierarchy(out):
    g = Gltf()
    pos = g.positions([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    nrm = g.accessor([0, 0, 1] * 3, FLOAT, "VEC3")
    g.add("meshes", {"name": "triangle", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm}}]})
    h = math.sqrt(0.5)
    g.doc["nodes"] = [
        {"name": "parent", "translation": [10, 0, 0], "children": [1, 2, 3, 5]},
        {"name": "trs", "translation": [0, 5, 0], "rotation": [0, 0, h, h], "scale": [2, 2, 2], "mesh": 0},
        {"name": "matrix", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1], "children": [4]},
        {"name": "mirror", "scale": [-1, 1, 1], "mesh": 0},
        {"name": "child", "translation": [1, 0, 0], "mesh": 0},
        {"name": "hidden", "scale": [0, 0, 0], "mesh": 0},
        {"name": "other scene", "mesh": 0},
    ]
    g.doc["scene"] = 1
    g.doc["scenes"] = [{"name": "other", "nodes": [6]}, {"name": "main", "nodes": [0]}]
    g.write_gltf(out / "hierarchy.gltf")


def accessors(out):
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_mesh_quantization"]
    g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    prims = []
    # 0: interleaved: POSITION float3 (12 bytes) + NORMAL normalized int8 x3 + pad + TEXCOORD_0 normalized uint16 x2.
    verts = square(0)
    uvs = [(0, 65535), (65535, 65535), (65535, 0), (0, 0)]
    data = b"".join(struct.pack("<3f3bx2H", *p, 0, 0, 127, *uv) for p, uv in zip(verts, uvs))
    v = g.view(data, stride=20, target=34962)
    prims.append({"attributes": {
        "POSITION": g.accessor([c for p in verts for c in p], FLOAT, "VEC3", minmax=True, view=v, count=4),
        "NORMAL": g.accessor(None, BYTE, "VEC3", normalized=True, view=v, offset=12, count=4),
        "TEXCOORD_0": g.accessor(None, USHORT, "VEC2", normalized=True, view=v, offset=16, count=4)},
        "indices": g.accessor([0, 1, 2, 0, 2, 3], USHORT, "SCALAR")})
    # 1: sparse: vertex 3 of the square at x = 2 moves from (2, 1, 0) to (2, 2, 0).
    p1 = g.positions(square(2))
    g.doc["accessors"][p1]["sparse"] = {"count": 1, "indices": {"bufferView": g.view(struct.pack("<B", 3)), "componentType": UBYTE},
                                        "values": {"bufferView": g.view(struct.pack("<3f", 2, 2, 0))}}
    g.doc["accessors"][p1]["max"] = [3, 2, 0]
    prims.append({"attributes": {"POSITION": p1}, "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR")})
    # 2: no bufferView (all zeros) + sparse values for all three vertices.
    p2 = g.add("accessors", {"componentType": FLOAT, "type": "VEC3", "count": 3, "min": [4, 0, 0], "max": [5, 1, 0],
                             "sparse": {"count": 3, "indices": {"bufferView": g.view(struct.pack("<3I", 0, 1, 2)), "componentType": UINT},
                                        "values": {"bufferView": g.view(struct.pack("<9f", 4, 0, 0, 5, 0, 0, 4, 1, 0))}}})
    prims.append({"attributes": {"POSITION": p2}})
    # 3: KHR_mesh_quantization: int16 positions (not normalized), normalized uint8 UVs.
    prims.append({"attributes": {
        "POSITION": g.accessor([6, 0, 0, 7, 0, 0, 6, 1, 0], SHORT, "VEC3", minmax=True),
        "TEXCOORD_0": g.accessor([0, 0, 255, 0, 0, 51], UBYTE, "VEC2", normalized=True)}})
    g.add("meshes", {"name": "accessors", "primitives": prims})
    g.add("nodes", {"mesh": 0})
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0]}]
    g.write_glb(out / "accessors.glb")


def quad_mesh(g, name, x0, material=None, tangent=False):
    """A unit square at x = x0 facing +z with NORMAL and TEXCOORD_0 (and TANGENT)."""
    attrs = {"POSITION": g.positions(square(x0)), "NORMAL": g.accessor([0, 0, 1] * 4, FLOAT, "VEC3"),
             "TEXCOORD_0": g.accessor([0, 1, 1, 1, 1, 0, 0, 0], FLOAT, "VEC2")}
    if tangent:
        attrs["TANGENT"] = g.accessor([1, 0, 0, -1] * 4, FLOAT, "VEC4")
    prim = {"attributes": attrs, "indices": g.accessor([0, 1, 2, 0, 2, 3], USHORT, "SCALAR")}
    if material is not None:
        prim["material"] = material
    return g.add("meshes", {"name": name, "primitives": [prim]})


def materials(out):
    g = Gltf()
    (out / "textures").mkdir(exist_ok=True)
    (out / "textures" / "checker.png").write_bytes(CHECKER_4)
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior",
                               "KHR_materials_specular", "KHR_texture_transform"]
    g.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(CHECKER_2).decode()},
                       {"uri": "textures/checker.png"}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1}]
    g.doc["materials"] = [
        {"name": "factors", "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0.25, "roughnessFactor": 0.6}},
        {"name": "textured",
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
         "normalTexture": {"index": 1, "scale": 0.5, "extensions": {"KHR_texture_transform": {
             "offset": [0.5, 0], "rotation": 0.3, "scale": [2, 2]}}}},
        {"name": "lamp", "emissiveFactor": [1, 0.5, 0.25], "emissiveTexture": {"index": 0},
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
        {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.33}}},
        {"name": "coated", "pbrMetallicRoughness": {"metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {"specularFactor": 0, "specularColorFactor": [1, 0.9, 0.8],
                                                   "specularTexture": {"index": 1}}}},
        {"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.3, "pbrMetallicRoughness": {"metallicFactor": 0}},
        {"name": "veil", "alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "metallicFactor": 0}},
        {"name": "lamp2", "doubleSided": True, "emissiveFactor": [1, 1, 1]},
    ]
    names = ["factors", "textured", "lamp", "glass", "coated", "leaf", "veil", "lamp2"]
    nodes = [{"name": n, "mesh": quad_mesh(g, n, 2 * i, material=i)} for i, n in enumerate(names)]
    nodes.append({"name": "default", "mesh": quad_mesh(g, "default", 16)})
    nodes.append({"name": "tangents", "mesh": quad_mesh(g, "tangents", 18, material=1, tangent=True)})
    g.doc["nodes"] = nodes
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": list(range(len(nodes)))}]
    g.write_gltf(out / "materials.gltf", "materials.bin")


def cameras(out):
    g = Gltf()
    g.add("meshes", {"primitives": [{"attributes": {"POSITION": g.positions([(-1, -1, 0), (1, -1, 0), (0, 1, 0)])}}]})
    g.doc["cameras"] = [
        {"name": "ortho", "type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 100}},
        {"name": "wide", "type": "perspective", "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}},
        {"name": "front", "type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}},
    ]
    h = math.sqrt(0.5)
    g.doc["nodes"] = [
        {"name": "ortho", "camera": 0},
        {"name": "rig", "rotation": [0, h, 0, h], "children": [2]},
        {"name": "wide", "camera": 1, "translation": [0, 1, 5]},
        {"name": "front", "camera": 2, "translation": [0, 0, 10]},
        {"name": "triangle", "mesh": 0},
    ]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 3, 4]}]
    g.write_gltf(out / "cameras.gltf")


def no_camera(out):
    g = Gltf()
    c = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]  # corner i: bit0 x, bit1 y, bit2 z
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    idx = [i for a, b, cc, d in faces for i in (a, b, cc, a, cc, d)]
    g.add("meshes", {"name": "cube", "primitives": [{"attributes": {"POSITION": g.positions(c)},
                                                     "indices": g.accessor(idx, UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": "cube", "mesh": 0, "translation": [3, 2, 1]}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0]}]
    g.write_gltf(out / "no-camera.gltf")


def emissive(out):
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    img = g.image_view(CHECKER_4, "image/png")
    g.doc["textures"] = [{"source": img}]
    g.doc["materials"] = [
        {"name": "floor", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}},
        {"name": "panel", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
        {"name": "sign", "doubleSided": True, "emissiveFactor": [0, 0.5, 1],
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
    ]
    floor = [(-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2)]  # faces +y
    panel = [(-0.5, 2, -0.5), (0.5, 2, -0.5), (0.5, 2, 0.5), (-0.5, 2, 0.5)]  # faces -y (down)
    quad = [0, 1, 2, 0, 2, 3]
    g.add("meshes", {"name": "floor", "primitives": [{"attributes": {
        "POSITION": g.positions(floor), "TEXCOORD_0": g.accessor([0, 2, 2, 2, 2, 0, 0, 0], FLOAT, "VEC2")},
        "indices": g.accessor(quad, UBYTE, "SCALAR"), "material": 0}]})
    g.add("meshes", {"name": "panel", "primitives": [{"attributes": {"POSITION": g.positions(panel)},
                                                      "indices": g.accessor(quad, UBYTE, "SCALAR"), "material": 1}]})
    g.add("meshes", {"name": "sign", "primitives": [{"attributes": {
        "POSITION": g.positions([(-1, 0.2, -1), (1, 0.2, -1), (0, 1.4, -1)])}, "material": 2}]})
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}]
    g.doc["nodes"] = [{"mesh": 0}, {"mesh": 1}, {"mesh": 2},
                      {"camera": 0, "translation": [0, 1, 5]}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2, 3]}]
    g.write_glb(out / "emissive.glb")


def extensions(out):
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_variants", "KHR_materials_emissive_strength"]
    g.doc["extensions"] = {"KHR_materials_variants": {"variants": [{"name": "plain"}]}}
    g.add("meshes", {"primitives": [{"attributes": {"POSITION": g.positions([(0, 0, 0), (1, 0, 0), (0, 1, 0)])}}]})
    g.doc["nodes"] = [{"mesh": 0}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0]}]
    g.write_gltf(out / "extensions.gltf")


LAMBERT_08 = {"name": "lambert 0.8", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                              "roughnessFactor": 1},
              "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}


def floor_mesh(g, half):
    """A Lambertian (albedo 0.8) floor [-half, half]^2 in the plane y = 0, facing +y."""
    g.doc.setdefault("extensionsUsed", []).append("KHR_materials_specular")
    m = g.add("materials", LAMBERT_08)
    pts = [(-half, 0, -half), (-half, 0, half), (half, 0, half), (half, 0, -half)]
    return g.add("meshes", {"name": "floor", "primitives": [{"attributes": {"POSITION": g.positions(pts)},
                                                            "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR"),
                                                            "material": m}]})


def lights(out):
    """KHR_lights_punctual: a point, a spot and a directional light on rotated nodes."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    floor = floor_mesh(g, 5)
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "bulb", "type": "point", "color": [1, 0.5, 0.25], "intensity": 683},
        {"name": "spot", "type": "spot", "intensity": 1366, "range": 20, "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
        {"name": "sun", "type": "directional", "color": [0.5, 0.5, 1], "intensity": 341.5},
        {"name": "unused", "type": "point"},
    ]}}
    h = math.sqrt(0.5)
    g.doc["nodes"] = [
        {"name": "floor", "mesh": floor},
        {"name": "bulb", "translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        # -90 degrees about x: the node's -z (the way a light shines) becomes -y (down).
        {"name": "rig", "translation": [0, 4, 0], "rotation": [-h, 0, 0, h], "scale": [2, 2, 2], "children": [3]},
        {"name": "spot", "translation": [0.5, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        # 90 degrees about y: -z becomes -x.
        {"name": "sun", "rotation": [0, h, 0, h], "extensions": {"KHR_lights_punctual": {"light": 2}}},
    ]
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    g.add("nodes", {"name": "camera", "camera": 0, "translation": [0, 3, 8]})
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2, 4, 5]}]
    g.write_gltf(out / "lights.gltf")


POINT_LAMP_WATTS = 100.0


def point_lamp(out):
    """Blender's units: a point lamp of 100 W 2 m above a floor of albedo 0.8, written as Blender's
    exporter writes it (W / (4 pi) x 683 cd); a camera 1 m above the floor looks straight down at
    the spot below the lamp (yfov 0.1)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    floor = floor_mesh(g, 10)
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "lamp", "type": "point", "intensity": POINT_LAMP_WATTS / (4 * math.pi) * 683}]}}
    h = math.sqrt(0.5)
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.1, "aspectRatio": 1.0, "znear": 0.01}}]
    g.doc["nodes"] = [
        {"name": "floor", "mesh": floor},
        {"name": "lamp", "translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "camera", "camera": 0, "translation": [0, 1, 0], "rotation": [-h, 0, 0, h]},
    ]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2]}]
    g.write_gltf(out / "point-lamp.gltf")


TEXTURE_4 = [[(40 + 60 * x, 40 + 60 * y, 200 - 50 * x, 255) for x in range(4)] for y in range(4)]
# metallicRoughness: G = roughness 1 everywhere, B = metallic 0 or 1 in a 2x2 checker.
TEXTURE_MR = [[(0, 255, 0, 255), (0, 255, 255, 255)], [(0, 255, 255, 255), (0, 255, 0, 255)]]
TEXTURE_NORMAL = [[(255, 128, 255, 255)]]  # tangent-space (1, 0.004, 1): tilted about 39 degrees at scale 0.8


def data_png(width, height, rgba):
    return "data:image/png;base64," + base64.b64encode(png(width, height, rgba)).decode()


def textures(out):
    """Eight 2 x 2 quads in the plane z = 0 facing +z, side by side (quad i at x in [2.5 i, 2.5 i + 2],
    y in [0, 2]); UV (-0.75, -0.75) at the top left corner, (1.75, 1.75) at the bottom right, so that
    every wrap mode shows. Materials: metallic 0, roughness 1, specularFactor 0 (the Lambertian base
    alone), baseColorFactor (1, 0.5, 1, 1) times the texture."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular", "KHR_texture_transform"]
    g.doc["images"] = [{"uri": data_png(4, 4, TEXTURE_4)}, {"uri": data_png(2, 2, TEXTURE_MR)},
                       {"uri": data_png(1, 1, TEXTURE_NORMAL)}]
    nearest, linear, repeat, clamp, mirror = 9728, 9729, 10497, 33071, 33648
    g.doc["samplers"] = [{"magFilter": nearest, "wrapS": repeat, "wrapT": repeat},
                         {"magFilter": nearest, "wrapS": clamp, "wrapT": clamp},
                         {"magFilter": nearest, "wrapS": mirror, "wrapT": mirror},
                         {"magFilter": linear, "wrapS": repeat, "wrapT": mirror},
                         {"magFilter": nearest, "wrapS": clamp, "wrapT": repeat}]
    g.doc["textures"] = [{"source": 0, "sampler": i} for i in range(5)] + [{"source": 1, "sampler": 0},
                                                                          {"source": 2, "sampler": 0}]

    def mat(name, base_texture, **extra):
        pbr = {"baseColorFactor": [1, 0.5, 1, 1], "metallicFactor": 0, "roughnessFactor": 1,
               "baseColorTexture": base_texture}
        pbr.update(extra.pop("pbr", {}))
        m = {"name": name, "pbrMetallicRoughness": pbr,
             "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}
        m.update(extra)
        return m
    g.doc["materials"] = [
        mat("repeat", {"index": 0}), mat("clamp", {"index": 1}), mat("mirror", {"index": 2}),
        mat("transform", {"index": 4, "extensions": {"KHR_texture_transform": {
            "offset": [0.25, -0.5], "rotation": 0.5, "scale": [1.5, 0.75]}}}),
        mat("bilinear", {"index": 3}),
        mat("metalrough", {"index": 0}, pbr={"metallicFactor": 1, "metallicRoughnessTexture": {"index": 5}}),
        mat("normal", {"index": 0}, normalTexture={"index": 6, "scale": 0.8}),
        mat("normal-flat", {"index": 0}, normalTexture={"index": 6, "scale": 0.8}),  # a mesh without NORMAL
    ]
    uv = [-0.75, -0.75, 1.75, -0.75, 1.75, 1.75, -0.75, 1.75]
    for i, m in enumerate(g.doc["materials"]):
        x0 = 2.5 * i
        pos = [(x0, 2, 0), (x0 + 2, 2, 0), (x0 + 2, 0, 0), (x0, 0, 0)]  # top left, top right, bottom right, bottom left
        attrs = {"POSITION": g.positions(pos), "TEXCOORD_0": g.accessor(uv, FLOAT, "VEC2")}
        if m["name"] != "normal-flat":
            attrs["NORMAL"] = g.accessor([0, 0, 1] * 4, FLOAT, "VEC3")
        g.add("meshes", {"name": m["name"], "primitives": [{"attributes": attrs, "material": i,
                                                            "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": m["name"], "mesh": i} for i, m in enumerate(g.doc["materials"])]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": list(range(len(g.doc["nodes"])))}]
    g.write_gltf(out / "textures.gltf")


def alpha(out):
    """Quads as in textures(): 0 "mask" (MASK, cutoff 0.5, factor alpha 0.6 x texture alpha 1 or
    128/255: solid or a hole in a checker), 1 "blend" (BLEND, alpha 0.25), 2 "back" (opaque grey)
    at z = 0 behind 3 "ghost" (MASK, alpha 0.2: cut out everywhere) at z = 0.5, larger than it."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]
    holes = [[(40 + 60 * x, 40 + 60 * y, 200 - 50 * x, 255 if (x + y) % 2 == 0 else 128) for x in range(4)]
             for y in range(4)]
    g.doc["images"] = [{"uri": data_png(4, 4, holes)}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 10497, "wrapT": 10497}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]

    def mat(name, factor, **extra):
        pbr = {"baseColorFactor": factor, "metallicFactor": 0, "roughnessFactor": 1}
        pbr.update(extra.pop("pbr", {}))
        m = {"name": name, "pbrMetallicRoughness": pbr, "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}
        m.update(extra)
        return m
    g.doc["materials"] = [
        mat("mask", [1, 0.5, 1, 0.6], alphaMode="MASK", alphaCutoff=0.5, pbr={"baseColorTexture": {"index": 0}}),
        mat("blend", [1, 0.5, 1, 0.25], alphaMode="BLEND"),
        mat("back", [0.6, 0.6, 0.6, 1]),
        mat("ghost", [1, 1, 1, 0.2], alphaMode="MASK"),
    ]
    uv = [-0.75, -0.75, 1.75, -0.75, 1.75, 1.75, -0.75, 1.75]
    quads = [(0.0, 0.0, 0.0, 2.0), (2.5, 0.0, 0.0, 2.0), (5.0, 0.0, 0.0, 2.0), (4.9, -0.1, 0.5, 2.2)]  # x0, y0, z, size
    for i, (x0, y0, z, size) in enumerate(quads):
        pos = [(x0, y0 + size, z), (x0 + size, y0 + size, z), (x0 + size, y0, z), (x0, y0, z)]
        attrs = {"POSITION": g.positions(pos), "NORMAL": g.accessor([0, 0, 1] * 4, FLOAT, "VEC3"),
                 "TEXCOORD_0": g.accessor(uv, FLOAT, "VEC2")}
        g.add("meshes", {"name": g.doc["materials"][i]["name"], "primitives": [{
            "attributes": attrs, "material": i, "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": m["name"], "mesh": i} for i, m in enumerate(g.doc["materials"])]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": list(range(len(g.doc["nodes"])))}]
    g.write_gltf(out / "alpha.gltf")


VC_C00 = (0.2, 0.9, 0.1, 0.0)  # COLOR_0 at (x, y) = (x0, 0): c00 + x dcdx + y dcdy on each 2 x 2 quad
VC_DCDX = (0.3, -0.2, 0.1, 0.5)
VC_DCDY = (0.1, 0.0, 0.35, 0.0)


def vertex_colors(out):
    """COLOR_0 (tests/gpu/test_gpu_vertex_colors.cpp): four 2 x 2 quads at z = 0 facing +z (quad i at
    x in [3 i, 3 i + 2], y in [0, 2]) of a Lambertian base colour 0.8, whose corner colours are
    VC_C00 + x VC_DCDX + y VC_DCDY (x, y relative to the quad's corner): 0 "ushort" RGBA as
    normalized uint16, 1 "mask" RGBA as float under alphaMode MASK (cutoff 0.5: the left half, alpha
    < 0.5, is a hole), 2 "float3" RGB as float, 3 "ubyte" RGBA as normalized uint8."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]

    def mat(name, **extra):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 1},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}
        m.update(extra)
        return m
    g.doc["materials"] = [mat("ushort"), mat("mask", alphaMode="MASK", alphaCutoff=0.5), mat("float3"), mat("ubyte")]
    corners = [(0, 0), (2, 0), (2, 2), (0, 2)]
    # Vertex attribute elements must be 4-byte aligned: 8- and 16-bit colours are VEC4.
    for i, (ctype, n) in enumerate(((USHORT, 4), (FLOAT, 4), (FLOAT, 3), (UBYTE, 4))):
        x0 = 3.0 * i
        cols = [[VC_C00[k] + x * VC_DCDX[k] + y * VC_DCDY[k] for k in range(n)] for x, y in corners]
        if ctype == FLOAT:
            values = [c for col in cols for c in col]
        else:
            scale = 65535 if ctype == USHORT else 255
            values = [int(round(c * scale)) for col in cols for c in col]
        attrs = {"POSITION": g.positions([(x0 + x, y, 0.0) for x, y in corners]),
                 "COLOR_0": g.accessor(values, ctype, "VEC4" if n == 4 else "VEC3", normalized=ctype != FLOAT)}
        g.add("meshes", {"name": g.doc["materials"][i]["name"], "primitives": [{
            "attributes": attrs, "material": i, "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": m["name"], "mesh": i} for i, m in enumerate(g.doc["materials"])]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2, 3]}]
    g.write_gltf(out / "vertex-colors.gltf")


def unlit(out):
    """KHR_materials_unlit (tests/gpu/test_gpu_unlit.cpp): two 2 x 2 quads at z = 0 of an unlit base
    colour (0.2, 0.4, 0.6): quad 0 at x in [0, 2] facing +z, quad 1 at x in [3, 5] facing -z (its
    back to a camera on +z; single-sided)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_unlit"]
    g.doc["materials"] = [{"name": "unlit", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1]},
                           "extensions": {"KHR_materials_unlit": {}}}]
    for i, x0 in enumerate((0.0, 3.0)):
        pts = [(x0, 0, 0), (x0 + 2, 0, 0), (x0 + 2, 2, 0), (x0, 2, 0)]
        idx = [0, 1, 2, 0, 2, 3] if i == 0 else [0, 2, 1, 0, 3, 2]
        g.add("meshes", {"name": "front" if i == 0 else "back", "primitives": [{
            "attributes": {"POSITION": g.positions(pts)}, "material": 0, "indices": g.accessor(idx, UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": "front", "mesh": 0}, {"name": "back", "mesh": 1}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1]}]
    g.write_gltf(out / "unlit.gltf")


def emissive_texture(out):
    """Quad "lamp" as in textures() (x in [0, 2], y in [0, 2], z = 0, facing +z) with emissiveFactor
    (1, 0.5, 1) x strength 2 x the 4x4 colour texture (nearest, repeat); a "panel" of the same
    material (y = -3, x in [11, 13], z in [-1, 1], facing down) over a grey Lambertian floor
    (y = -5, x in [9, 15], z in [-3, 3]), out of the first camera's view."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular", "KHR_materials_emissive_strength"]
    g.doc["images"] = [{"uri": data_png(4, 4, TEXTURE_4)}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 10497, "wrapT": 10497}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    g.doc["materials"] = [
        {"name": "lamp", "emissiveFactor": [1, 0.5, 1], "emissiveTexture": {"index": 0},
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
    ]
    uv = [-0.75, -0.75, 1.75, -0.75, 1.75, 1.75, -0.75, 1.75]
    quads = [("lamp", 0, [(0, 2, 0), (2, 2, 0), (2, 0, 0), (0, 0, 0)]),
             ("panel", 0, [(11, -3, 1), (13, -3, 1), (13, -3, -1), (11, -3, -1)]),   # faces -y
             ("floor", 1, [(9, -5, -3), (15, -5, -3), (15, -5, 3), (9, -5, 3)])]     # faces +y
    for name, material, pos in quads:
        attrs = {"POSITION": g.positions(pos), "TEXCOORD_0": g.accessor(uv, FLOAT, "VEC2")}
        g.add("meshes", {"name": name, "primitives": [{"attributes": attrs, "material": material,
                                                       "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": q[0], "mesh": i} for i, q in enumerate(quads)]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2]}]
    g.write_gltf(out / "emissive-texture.gltf")

def emissive_spot(out):
    """A panel of 8 x 8 cells (128 triangles, 2 per cell) at y = 2 over x, z in [-1, 1], facing down,
    UV = ((x + 1) / 2, (z + 1) / 2), emissiveFactor 1 x strength 8 x a 32 x 32 sRGB texture (bilinear,
    clamp) that is (1, 1, 1) / 255 everywhere (linear 3.0e-4) but for texels x 8-11, y 20-23, which
    are (255, 230, 200): one cell's worth of the texture (cell 2, 5) holds ~98 % of the light. Every
    triangle has the same area and some emission (none is black), so the light pick before issue 6
    (the texture's mean for every triangle) picked them all alike: --light-pick uniform. A grey
    Lambertian floor (y = 0, x, z in [-2, 2], specularFactor 0) faces up."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular", "KHR_materials_emissive_strength"]
    tex = [[(255, 230, 200, 255) if 8 <= x < 12 and 20 <= y < 24 else (1, 1, 1, 255) for x in range(32)] for y in range(32)]
    g.doc["images"] = [{"uri": data_png(32, 32, tex)}]
    g.doc["samplers"] = [{"magFilter": 9729, "wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}]
    g.doc["materials"] = [
        {"name": "spot", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0},
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
    ]
    n = 8
    pos, uv, idx = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -1 + 2 * i / n, -1 + 2 * j / n
            pos.append((x, 2.0, z))
            uv += [i / n, j / n]
    for j in range(n):
        for i in range(n):
            a, b, c, d = (j + 1) * (n + 1) + i, (j + 1) * (n + 1) + i + 1, j * (n + 1) + i + 1, j * (n + 1) + i
            idx += [a, c, b, a, d, c]  # counter-clockwise seen from below: faces -y
    spot = {"POSITION": g.positions(pos), "TEXCOORD_0": g.accessor(uv, FLOAT, "VEC2")}
    g.add("meshes", {"name": "spot", "primitives": [{"attributes": spot, "material": 0,
                                                      "indices": g.accessor(idx, UBYTE, "SCALAR")}]})
    floor = {"POSITION": g.positions([(-2, 0, -2), (2, 0, -2), (2, 0, 2), (-2, 0, 2)])}
    g.add("meshes", {"name": "floor", "primitives": [{"attributes": floor, "material": 1,
                                                       "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": "spot", "mesh": 0}, {"name": "floor", "mesh": 1}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1]}]
    g.write_gltf(out / "emissive-spot.gltf")


def add_half_quads(g, uv_accessors):
    """One 2 x 2 quad per material of g, quad i at x in [2.5 i, 2.5 i + 2], y in [0, 2] in the plane
    z = 0 facing +z (tests/gpu/half_quads.h), each its own mesh and node, and the default scene.
    uv_accessors() adds a quad's UV accessors (corners: top left, top right, bottom right, bottom left)."""
    for i, m in enumerate(g.doc["materials"]):
        x0 = 2.5 * i
        pos = [(x0, 2, 0), (x0 + 2, 2, 0), (x0 + 2, 0, 0), (x0, 0, 0)]  # top left, top right, bottom right, bottom left
        attrs = {"POSITION": g.positions(pos), "NORMAL": g.accessor([0, 0, 1] * 4, FLOAT, "VEC3")}
        attrs.update(uv_accessors())
        g.add("meshes", {"name": m["name"], "primitives": [{"attributes": attrs, "material": i,
                                                            "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR")}]})
    g.doc["nodes"] = [{"name": m["name"], "mesh": i} for i, m in enumerate(g.doc["materials"])]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": list(range(len(g.doc["nodes"])))}]


def specular_textures(out):
    """KHR_materials_specular specularTexture (A) and specularColorTexture (RGB, sRGB): see the
    docstring at the top. RGB of the specular textures and A of the colour one are decoys: the
    kernel must read the other channels."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]
    g.doc["images"] = [{"uri": data_png(2, 1, [[(255, 255, 255, 0), (0, 0, 0, 255)]])},
                       {"uri": data_png(1, 1, [[(0, 0, 0, 128)]])},
                       {"uri": data_png(2, 1, [[(255, 255, 255, 0), (0, 128, 255, 0)]])}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"] = [{"source": i, "sampler": 0} for i in range(3)]

    def mat(name, spec):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.1, 0.1, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 0.5},
                "extensions": {"KHR_materials_specular": spec}}
    g.doc["materials"] = [
        mat("specular-half", {"specularTexture": {"index": 0}}),
        mat("specular-uniform", {"specularTexture": {"index": 1}}),
        mat("specular-color-half", {"specularColorFactor": [1, 1, 1], "specularColorTexture": {"index": 2}}),
    ]
    add_half_quads(g, lambda: {"TEXCOORD_0": g.accessor([0, 0, 1, 0, 1, 1, 0, 1], FLOAT, "VEC2")})
    g.write_gltf(out / "specular-textures.gltf")


def transmission_textures(out):
    """KHR_materials_transmission transmissionTexture (R, linear): see the docstring at the top.
    G, B and A are decoys (the opposite of R)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_transmission"]
    g.doc["images"] = [{"uri": data_png(2, 1, [[(0, 255, 255, 255), (255, 0, 0, 0)]])},
                       {"uri": data_png(1, 1, [[(128, 0, 0, 0)]])}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"] = [{"source": i, "sampler": 0} for i in range(2)]
    g.doc["materials"] = [
        {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0,
                                                "roughnessFactor": 0.5},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1, "transmissionTexture": {"index": i}}}}
        for i, name in enumerate(["transmission-half", "transmission-uniform"])]
    add_half_quads(g, lambda: {"TEXCOORD_0": g.accessor([0, 0, 1, 0, 1, 1, 0, 1], FLOAT, "VEC2")})
    g.write_gltf(out / "transmission-textures.gltf")


def layer_textures(out):
    """KHR_materials_clearcoat and KHR_materials_sheen textures: see the docstring at the top."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular"]
    g.doc["images"] = [{"uri": data_png(2, 1, [[(0, 255, 255, 255), (255, 0, 0, 0)]])},      # R 0 | 1
                       {"uri": data_png(2, 1, [[(255, 0, 255, 255), (0, 255, 0, 0)]])},      # G 0 | 1
                       {"uri": data_png(2, 1, [[(255, 255, 255, 0), (0, 128, 255, 0)]])},    # RGB white | (0, 128, 255)
                       {"uri": data_png(2, 1, [[(255, 255, 255, 0), (0, 0, 0, 255)]])},      # A 0 | 1
                       {"uri": data_png(1, 1, [[(171, 128, 247, 255)]])}]                    # a tilted normal
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"] = [{"source": i, "sampler": 0} for i in range(5)]

    def mat(name, ext, base=0.1, specular=None):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [base, base, base, 1], "metallicFactor": 0,
                                                     "roughnessFactor": 0.5},
             "extensions": ext}
        if specular is not None:
            m["extensions"]["KHR_materials_specular"] = {"specularFactor": specular}
        return m
    g.doc["materials"] = [
        mat("clearcoat-half", {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.2,
                                                           "clearcoatTexture": {"index": 0}}}),
        mat("clearcoat-roughness-half", {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 1,
                                                                     "clearcoatRoughnessTexture": {"index": 1}}}),
        mat("sheen-color-half", {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.5,
                                                         "sheenColorTexture": {"index": 2}}}),
        mat("sheen-roughness-half", {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 1,
                                                             "sheenRoughnessTexture": {"index": 3}}}),
        mat("clearcoat-normal", {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatRoughnessFactor": 0.3,
                                                             "clearcoatNormalTexture": {"index": 4, "scale": 1}}},
            base=0.0, specular=0),
    ]
    add_half_quads(g, lambda: {"TEXCOORD_0": g.accessor([0, 0, 1, 0, 1, 1, 0, 1], FLOAT, "VEC2"),
                               "TANGENT": g.accessor([1, 0, 0, 1] * 4, FLOAT, "VEC4")})
    g.write_gltf(out / "layer-textures.gltf")


def texcoord1(out):
    """textureInfo.texCoord 1: see the docstring at the top."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular"]
    g.doc["images"] = [{"uri": data_png(2, 1, [[(255, 64, 0, 255), (0, 64, 255, 255)]])},
                       {"uri": data_png(2, 1, [[(255, 255, 255, 0), (0, 0, 0, 255)]])}]
    g.doc["samplers"] = [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"] = [{"source": i, "sampler": 0} for i in range(2)]
    g.doc["materials"] = [
        {"name": "uv1-base", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}, "metallicFactor": 0,
                                                      "roughnessFactor": 0.5}},
        {"name": "uv1-specular", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.1, 0.1, 1], "metallicFactor": 0,
                                                          "roughnessFactor": 0.5},
         "extensions": {"KHR_materials_specular": {"specularTexture": {"index": 1, "texCoord": 1}}}},
    ]
    add_half_quads(g, lambda: {"TEXCOORD_0": g.accessor([1, 0, 0, 0, 0, 1, 1, 1], FLOAT, "VEC2"),  # mirrored
                               "TEXCOORD_1": g.accessor([0, 0, 65535, 0, 65535, 65535, 0, 65535], USHORT, "VEC2",
                                                        normalized=True)})
    g.write_gltf(out / "texcoord1.gltf")


def blob(rings=10, segments=16):
    """A unit-radius-0.5 sphere with a lump towards +x (so a mirror shows): vertices and per-vertex
    NORMALs (the sphere's: the shading normals need not be the lump's), counter-clockwise outside."""
    pos, nrm = [], []
    for j in range(rings + 1):
        th = math.pi * j / rings
        for i in range(segments + 1):
            ph = 2 * math.pi * i / segments
            d = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            r = 0.5 * (1 + 0.6 * max(0.0, d[0]) ** 2)
            pos.append(tuple(round(r * c, 6) for c in d))
            nrm.append(tuple(round(c, 6) for c in d))
    idx = []
    for j in range(rings):
        for i in range(segments):
            a, b = j * (segments + 1) + i, j * (segments + 1) + i + 1
            c, e = (j + 1) * (segments + 1) + i + 1, (j + 1) * (segments + 1) + i
            if j > 0:
                idx += [a, b, e]
            if j < rings - 1:
                idx += [b, c, e]
    return pos, nrm, idx


def instances(out):
    """Meshes used by several nodes (vkpath stores each once with --instancing auto)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_emissive_strength"]
    g.doc["materials"] = [
        {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.35, 1], "metallicFactor": 0, "roughnessFactor": 0.45}},
        {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_specular": {"specularFactor": 0}}},
        {"name": "light", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}},
        {"name": "lamp", "emissiveFactor": [1, 0.6, 0.3], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3}},
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}},
    ]
    pos, nrm, idx = blob()
    g.add("meshes", {"name": "blob", "primitives": [{
        "attributes": {"POSITION": g.positions(pos), "NORMAL": g.accessor([c for n in nrm for c in n], FLOAT, "VEC3")},
        "indices": g.accessor(idx, USHORT, "SCALAR"), "material": 0}]})
    tet = [(0, 0.6, 0), (-0.35, 0, -0.25), (0.4, 0, -0.2), (0.05, 0, 0.4)]  # apex, base
    g.add("meshes", {"name": "tetrahedron", "primitives": [{
        "attributes": {"POSITION": g.positions(tet)},
        "indices": g.accessor([0, 3, 2, 0, 2, 1, 0, 1, 3, 1, 2, 3], UBYTE, "SCALAR"), "material": 1}]})
    floor = [(-4, 0, 3), (4, 0, 3), (4, 0, -4), (-4, 0, -4)]
    g.add("meshes", {"name": "floor", "primitives": [{"attributes": {"POSITION": g.positions(floor)},
                                                      "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR"), "material": 2}]})
    panel = [(-1, 3, 1), (1, 3, 1), (1, 3, -1), (-1, 3, -1)]  # faces -y
    g.add("meshes", {"name": "panel", "primitives": [{"attributes": {"POSITION": g.positions(panel)},
                                                      "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR"), "material": 3}]})
    lamp = [(-0.15, 0, 0), (0.15, 0, 0), (0.15, 0.3, 0), (-0.15, 0.3, 0)]  # faces +z
    g.add("meshes", {"name": "lamp", "primitives": [{"attributes": {"POSITION": g.positions(lamp)},
                                                     "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR"), "material": 4}]})
    s30 = math.sin(math.radians(15))
    g.doc["nodes"] = [
        {"name": "blob plain", "mesh": 0, "translation": [-1.3, 0.55, 0]},
        {"name": "blob rotated", "mesh": 0, "translation": [0, 0.55, 0], "rotation": [0, 0.7071067812, 0, 0.7071067812]},
        {"name": "blob stretched", "mesh": 0, "translation": [1.35, 0.4, 0], "scale": [1.4, 0.6, 0.9]},
        {"name": "blob mirrored", "mesh": 0, "translation": [-0.7, 0.55, 1.3], "scale": [-1, 1, 1]},
        {"name": "tilted parent", "translation": [0.7, 0.6, 1.3], "rotation": [0, 0, s30, math.cos(math.radians(15))], "children": [5]},
        {"name": "blob mirrored child", "mesh": 0, "scale": [0.8, -0.8, 0.8]},
        {"name": "glass", "mesh": 1, "translation": [-0.5, 0, -1.3]},
        {"name": "glass mirrored", "mesh": 1, "translation": [0.8, 0, -1.3], "scale": [1, 1, -1.3]},
        {"name": "floor", "mesh": 2},
        {"name": "panel", "mesh": 3},
        {"name": "lamp left", "mesh": 4, "translation": [-2.5, 0, -1]},
        {"name": "lamp right", "mesh": 4, "translation": [2.5, 0, -1]},
        {"name": "camera", "camera": 0, "translation": [0, 3.0, 6.6], "rotation": [-0.2164396139, 0, 0, 0.9762960071]},  # 25 degrees down
    ]
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1, "znear": 0.01}}]
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2, 3, 4, 6, 7, 8, 9, 10, 11, 12]}]
    g.write_gltf(out / "instances.gltf")


def grid(triangles, path):
    """A height field y = 0.05 sin(8x) cos(8z) on [-1,1]^2 with n x n quads, 2 n^2 >= triangles."""
    n = max(1, math.ceil(math.sqrt(triangles / 2)))
    g = Gltf()
    pos, nrm = array.array("f"), array.array("f")
    for j in range(n + 1):
        z = -1 + 2 * j / n
        for i in range(n + 1):
            x = -1 + 2 * i / n
            y = 0.05 * math.sin(8 * x) * math.cos(8 * z)
            dx, dz = 0.4 * math.cos(8 * x) * math.cos(8 * z), -0.4 * math.sin(8 * x) * math.sin(8 * z)
            inv = 1 / math.sqrt(dx * dx + 1 + dz * dz)
            pos.extend((x, y, z))
            nrm.extend((-dx * inv, inv, -dz * inv))
    idx = array.array("I")
    for j in range(n):
        row, nxt = j * (n + 1), (j + 1) * (n + 1)
        for i in range(n):
            a, b, c, d = row + i, row + i + 1, nxt + i + 1, nxt + i  # counter-clockwise seen from +y
            idx.extend((a, d, c, a, c, b))
    if sys.byteorder != "little":
        for arr in (pos, nrm, idx):
            arr.byteswap()
    nv = (n + 1) ** 2
    p = g.add("accessors", {"bufferView": g.view(pos.tobytes()), "componentType": FLOAT, "type": "VEC3", "count": nv,
                            "min": [-1, -0.05, -1], "max": [1, 0.05, 1]})
    q = g.add("accessors", {"bufferView": g.view(nrm.tobytes()), "componentType": FLOAT, "type": "VEC3", "count": nv})
    i = g.add("accessors", {"bufferView": g.view(idx.tobytes()), "componentType": UINT, "type": "SCALAR", "count": len(idx)})
    g.doc["materials"] = [{"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1], "metallicFactor": 0}},
                          {"name": "panel", "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}}]
    g.add("meshes", {"name": "grid", "primitives": [{"attributes": {"POSITION": p, "NORMAL": q}, "indices": i, "material": 0}]})
    panel = g.positions([(-0.3, 1, -0.3), (0.3, 1, -0.3), (0.3, 1, 0.3), (-0.3, 1, 0.3)])
    g.add("meshes", {"name": "panel", "primitives": [{"attributes": {"POSITION": panel},
                                                      "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR"), "material": 1}]})
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1, "znear": 0.01}}]
    g.doc["nodes"] = [{"mesh": 0}, {"mesh": 1},
                      {"camera": 0, "translation": [0, 1.6, 2.2], "rotation": [-0.2588190451, 0, 0, 0.9659258263]}]  # 30 degrees down
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": [0, 1, 2]}]
    g.write_glb(path)
    print("%s: %d triangles, %d vertices, %d bytes" % (path, 2 * n * n + 2, nv + 4, path.stat().st_size))


def instanced_blobs(count, triangles, path):
    """count instances of one blob of >= triangles triangles on a grid (see the usage above)."""
    rings = max(4, math.ceil(math.sqrt(triangles / 4)))
    segments = 2 * rings
    pos, nrm = array.array("f"), array.array("f")
    for j in range(rings + 1):
        th = math.pi * j / rings
        for i in range(segments + 1):
            ph = 2 * math.pi * i / segments
            d = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            r = 0.5 * (1 + 0.6 * max(0.0, d[0]) ** 2 + 0.03 * math.sin(9 * th) * math.cos(7 * ph))
            pos.extend(r * c for c in d)
            nrm.extend(d)
    idx = array.array("I")
    for j in range(rings):
        for i in range(segments):
            a, b = j * (segments + 1) + i, j * (segments + 1) + i + 1
            c, e = (j + 1) * (segments + 1) + i + 1, (j + 1) * (segments + 1) + i
            if j > 0:
                idx.extend((a, b, e))
            if j < rings - 1:
                idx.extend((b, c, e))
    if sys.byteorder != "little":
        for arr in (pos, nrm, idx):
            arr.byteswap()
    g = Gltf()
    nv = len(pos) // 3
    p = g.add("accessors", {"bufferView": g.view(pos.tobytes()), "componentType": FLOAT, "type": "VEC3", "count": nv,
                            "min": [-0.8, -0.52, -0.52], "max": [0.8, 0.52, 0.52]})
    q = g.add("accessors", {"bufferView": g.view(nrm.tobytes()), "componentType": FLOAT, "type": "VEC3", "count": nv})
    k = g.add("accessors", {"bufferView": g.view(idx.tobytes()), "componentType": UINT, "type": "SCALAR", "count": len(idx)})
    g.doc["materials"] = [
        {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.35, 1], "metallicFactor": 0, "roughnessFactor": 0.45}},
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0}},
        {"name": "light", "emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}}]
    g.add("meshes", {"name": "blob", "primitives": [{"attributes": {"POSITION": p, "NORMAL": q}, "indices": k, "material": 0}]})
    side = math.ceil(math.sqrt(count))
    half = 0.75 * side
    g.add("meshes", {"name": "floor", "primitives": [{"attributes": {"POSITION": g.positions(
        [(-half - 1, 0, half + 1), (half + 1, 0, half + 1), (half + 1, 0, -half - 1), (-half - 1, 0, -half - 1)])},
        "indices": g.accessor([0, 1, 2, 0, 2, 3], UBYTE, "SCALAR"), "material": 1}]})
    h = 2.0 + side
    g.add("meshes", {"name": "panel", "primitives": [{"attributes": {"POSITION": g.positions(
        [(-half, h, half), (half, h, half), (half, h, -half), (-half, h, -half)])},
        "indices": g.accessor([0, 2, 1, 0, 3, 2], UBYTE, "SCALAR"), "material": 2}]})
    nodes = []
    for n in range(count):
        x, z = n % side, n // side
        a = 0.37 * n  # turn about y
        sc = 0.8 + 0.4 * ((n * 7919) % 13) / 12
        sx = -sc if n % 3 == 2 else sc
        nodes.append({"mesh": 0, "translation": [1.5 * x - 0.75 * (side - 1), 0.55 * sc, 1.5 * z - 0.75 * (side - 1)],
                      "rotation": [0, math.sin(a / 2), 0, math.cos(a / 2)], "scale": [sx, sc, sc]})
    nodes += [{"mesh": 1}, {"mesh": 2},
              {"camera": 0, "translation": [0, 0.9 * side + 1.5, 1.2 * side + 2.5], "rotation": [-0.3007057995, 0, 0, 0.9537169507]}]  # 35 degrees down
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1, "znear": 0.01}}]
    g.doc["nodes"] = nodes
    g.doc["scene"] = 0
    g.doc["scenes"] = [{"nodes": list(range(len(nodes)))}]
    g.write_glb(path)
    print("%s: %d instances of %d triangles (%d drawn), %d bytes" % (path, count, len(idx) // 3, count * len(idx) // 3,
                                                                     path.stat().st_size))


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--grid":
        grid(int(sys.argv[2]), pathlib.Path(sys.argv[3]))
        return
    if len(sys.argv) == 5 and sys.argv[1] == "--instances":
        instanced_blobs(int(sys.argv[2]), int(sys.argv[3]), pathlib.Path(sys.argv[4]))
        return
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent / "scenes" / "gltf"
    out.mkdir(parents=True, exist_ok=True)
    for write in (modes, hierarchy, accessors, materials, cameras, no_camera, emissive, extensions, textures, alpha, emissive_texture,
                  emissive_spot, instances, specular_textures, transmission_textures, layer_textures, texcoord1, lights, point_lamp, vertex_colors, unlit):
        write(out)


if __name__ == "__main__":
    main()
