# Blender script (run by tools/blender-reference.sh; Debian's Blender 3.4): a 2 x 2 plane subdivided
# into 4 x 4 squares with a float colour attribute per vertex, linear in x and y, as the base colour
# of its material, exported to glTF (COLOR_0, as Blender's exporter writes vertex colours) and
# rendered with Cycles to a linear EXR in a white world (radiance 1), for
# tests/gpu/test_gpu_blender_lamps.cpp: each pixel is then the colour itself.
#   blender -b --factory-startup --python tools/blender/vertex_colors.py -- OUT.gltf OUT.exr SIZE SPP
# The exported material is Principled (roughness 1, specular 0, base colour from the attribute);
# Cycles renders a pure Diffuse BSDF of the attribute's colour, one bounce.
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
bpy.ops.object.mode_set(mode="EDIT")
bpy.ops.mesh.subdivide(number_cuts=3)
bpy.ops.object.mode_set(mode="OBJECT")
mesh = obj.data
attr = mesh.color_attributes.new("Col", "FLOAT_COLOR", "POINT")
for i, v in enumerate(mesh.vertices):
    x, y = v.co.x, v.co.y
    attr.data[i].color = (0.5 + 0.4 * x, 0.5 + 0.3 * y, 0.3 + 0.2 * x * y, 1.0)
mat = bpy.data.materials.new("vc")
mat.use_nodes = True
nt = mat.node_tree
bsdf = nt.nodes["Principled BSDF"]
bsdf.inputs["Roughness"].default_value = 1.0
bsdf.inputs["Specular"].default_value = 0.0
ca = nt.nodes.new("ShaderNodeVertexColor")
ca.layer_name = "Col"
nt.links.new(ca.outputs["Color"], bsdf.inputs["Base Color"])
mesh.materials.append(mat)
camera_down(scene, 4.0, 30.0)
world_color(scene, (1.0, 1.0, 1.0))
image_size(scene, size)  # before the export: the camera's aspectRatio
bpy.ops.export_scene.gltf(filepath=out_gltf, export_format="GLTF_SEPARATE", export_cameras=True, export_colors=True)
diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
nt.links.new(ca.outputs["Color"], diffuse.inputs["Color"])
nt.links.new(diffuse.outputs["BSDF"], nt.nodes["Material Output"].inputs["Surface"])
render_cycles(scene, spp, out_exr, max_bounces=1)
