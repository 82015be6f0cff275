# Blender script (run by tools/blender-reference.sh; Debian's Blender 3.4): a 2 x 2 plane under a
# sun lamp (10 W/m^2, 20 degrees from the vertical) in a black world, its material a clear coat
# (clearcoat 1, clearcoat roughness 0.3) over a black base without specular, exported to glTF
# (KHR_materials_clearcoat, KHR_lights_punctual) and rendered with Cycles to a linear EXR, for
# tests/gpu/test_gpu_blender_lamps.cpp.
#   blender -b --factory-startup --python tools/blender/clearcoat.py -- OUT.gltf OUT.exr SIZE SPP
# Cycles 3.4 does not render Principled's clear coat as KHR_materials_clearcoat defines it (its
# Principled v1 coat differs in lobe and weight: against vkpath's coat the ratio ran from 1.6 to
# 12.7 over this image), so Cycles renders what the extension specifies for a black base instead:
# a GGX Glossy BSDF of the coat's roughness (Cycles' GGX: alpha = roughness^2) times the coat's
# Fresnel at normal incidence, 0.04 (the camera looks straight down and the sun is 20 degrees off,
# so every half vector is within 25 degrees of the view: Schlick's Fresnel there is 0.04 within
# 0.2 %).
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import camera_down, image_size, render_cycles, world_color  # noqa: E402

out_gltf, out_exr, size, spp = sys.argv[sys.argv.index("--") + 1:][:4]
size, spp = int(size), int(spp)
COAT_ROUGHNESS = 0.3
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.mesh.primitive_plane_add(size=2.0)
obj = bpy.context.active_object
mat = bpy.data.materials.new("coat")
mat.use_nodes = True
nt = mat.node_tree
bsdf = nt.nodes["Principled BSDF"]
bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
bsdf.inputs["Roughness"].default_value = 1.0
bsdf.inputs["Specular"].default_value = 0.0
bsdf.inputs["Clearcoat"].default_value = 1.0
bsdf.inputs["Clearcoat Roughness"].default_value = COAT_ROUGHNESS
obj.data.materials.append(mat)
sun = bpy.data.lights.new("sun", "SUN")
sun.energy = 10.0
sun.angle = 0.0
sun_object = bpy.data.objects.new("sun", sun)
sun_object.rotation_euler = (math.radians(20.0), 0.0, 0.0)
scene.collection.objects.link(sun_object)
camera_down(scene, 4.0, 30.0)
world_color(scene, (0.0, 0.0, 0.0))
image_size(scene, size)  # before the export: the camera's aspectRatio
bpy.ops.export_scene.gltf(filepath=out_gltf, export_format="GLTF_SEPARATE", export_cameras=True, export_lights=True)
# What Cycles renders: 0.04 x GGX Glossy (Mix Shader: 0.96 of black, 0.04 of the glossy lobe).
glossy = nt.nodes.new("ShaderNodeBsdfGlossy")
glossy.distribution = "GGX"
glossy.inputs["Roughness"].default_value = COAT_ROUGHNESS
glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
black = nt.nodes.new("ShaderNodeBsdfDiffuse")
black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
mix = nt.nodes.new("ShaderNodeMixShader")
mix.inputs["Fac"].default_value = 0.96
nt.links.new(glossy.outputs["BSDF"], mix.inputs[1])
nt.links.new(black.outputs["BSDF"], mix.inputs[2])
nt.links.new(mix.outputs["Shader"], nt.nodes["Material Output"].inputs["Surface"])
render_cycles(scene, spp, out_exr, max_bounces=1)
