# Blender script (run by tools/blender-reference.sh; Debian's Blender 3.4): a 2 x 2 plane whose
# base colour is a 4 x 4 float image texture of 16 colours (linear interpolation, extend at the
# edges), exported to glTF (a 16-bit sRGB PNG, TEXCOORD_0, a LINEAR, CLAMP_TO_EDGE sampler) and rendered
# with Cycles to a linear EXR in a white world (radiance 1), for tests/gpu/test_gpu_blender_lamps.cpp:
# each pixel is then the texture's colour there.
#   blender -b --factory-startup --python tools/blender/textured.py -- OUT.gltf OUT.exr SIZE SPP
# The exported material is Principled (roughness 1, specular 0, base colour from the texture);
# Cycles renders a pure Diffuse BSDF of the texture's colour, one bounce.
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import camera_down, image_size, render_cycles, world_color  # noqa: E402

out_gltf, out_exr, size, spp = sys.argv[sys.argv.index("--") + 1:][:4]
size, spp = int(size), int(spp)
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=2.0)
obj = bpy.context.active_object
mesh = obj.data
# 16 colours, each channel a multiple of 1/15 (exact in 8 bits: the PNG the exporter writes holds
# what Cycles samples) from 3/15 up (the test compares ratios, which a channel near 0 would blur).
# A float (linear) image: Cycles filters it in linear space, as glTF asks (and vkpath does) for
# sRGB textures; a byte sRGB image Cycles would filter in sRGB space (measured: up to 42 % apart
# between texel centres). The exporter writes it as an 8-bit sRGB PNG; the linear values are the
# decodings of the exact bytes 17 n, so that PNG holds what Cycles samples.
def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


image = bpy.data.images.new("checker", 4, 4, alpha=False, float_buffer=True)
pixels = []
for j in range(4):
    for i in range(4):
        k = 4 * j + i
        srgb = [(3 + (3 * k) % 13) / 15.0, (3 + (5 * k + 2) % 13) / 15.0, (3 + (7 * k + 5) % 13) / 15.0]
        pixels += [srgb_to_linear(c) for c in srgb] + [1.0]
image.pixels = pixels
image.file_format = "PNG"
mat = bpy.data.materials.new("textured")
mat.use_nodes = True
nt = mat.node_tree
bsdf = nt.nodes["Principled BSDF"]
bsdf.inputs["Roughness"].default_value = 1.0
bsdf.inputs["Specular"].default_value = 0.0
tex = nt.nodes.new("ShaderNodeTexImage")
tex.image = image
tex.interpolation = "Linear"
tex.extension = "EXTEND"
nt.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
mesh.materials.append(mat)
camera_down(scene, 4.0, 30.0)
world_color(scene, (1.0, 1.0, 1.0))
image_size(scene, size)  # before the export: the camera's aspectRatio
bpy.ops.export_scene.gltf(filepath=out_gltf, export_format="GLTF_SEPARATE", export_cameras=True)
diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
nt.links.new(tex.outputs["Color"], diffuse.inputs["Color"])
nt.links.new(diffuse.outputs["BSDF"], nt.nodes["Material Output"].inputs["Surface"])
render_cycles(scene, spp, out_exr, max_bounces=1)
