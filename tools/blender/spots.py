# Blender script (run by tools/blender-reference.sh; Debian's Blender 3.4): three spot lamps of
# different cone sizes and blends (30 degrees blend 0, 60 degrees blend 0.15, 100 degrees blend 0.5;
# 300 W each, 3 m above the floor, pointing straight down, 6 m apart) over a floor of albedo 0.8,
# exported to glTF (KHR_lights_punctual) and rendered with Cycles to a linear EXR, for
# tests/gpu/test_gpu_blender_lamps.cpp. As lamps.py: Principled exported, Cycles renders a pure
# Diffuse BSDF, point lamps (radius 0), black world.
#   blender -b --factory-startup --python tools/blender/spots.py -- OUT.gltf OUT.exr SIZE SPP
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import camera_down, diffuse_floor, image_size, render_as_diffuse, render_cycles, world_color  # noqa: E402

out_gltf, out_exr, size, spp = sys.argv[sys.argv.index("--") + 1:][:4]
size, spp = int(size), int(spp)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
mat = diffuse_floor(24.0, 0.8)

for i, (size_degrees, blend) in enumerate(((30.0, 0.0), (60.0, 0.15), (100.0, 0.5))):
    data = bpy.data.lights.new("spot%d" % i, "SPOT")
    data.energy = 300.0
    data.shadow_soft_size = 0.0
    data.spot_size = math.radians(size_degrees)
    data.spot_blend = blend
    obj = bpy.data.objects.new("spot%d" % i, data)
    obj.location = (6.0 * (i - 1), 0.0, 3.0)  # a light points along its -Z: straight down
    scene.collection.objects.link(obj)

camera_down(scene, 14.0, 70.0)
world_color(scene, (0.0, 0.0, 0.0))
image_size(scene, size)  # before the export: the camera's aspectRatio
bpy.ops.export_scene.gltf(filepath=out_gltf, export_format="GLTF_SEPARATE", export_lights=True, export_cameras=True)
render_as_diffuse(mat, 0.8)
render_cycles(scene, spp, out_exr, max_bounces=1)
