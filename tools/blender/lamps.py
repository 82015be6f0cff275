# Blender script (run by tools/blender-reference.sh; Debian's Blender 3.4): a floor of albedo 0.8
# lit by a point lamp, a spot lamp and a sun, exported to glTF (KHR_lights_punctual, as Blender's
# exporter writes lamps) and rendered with Cycles to a linear EXR, for tests/gpu/test_gpu_blender_lamps.cpp.
#   blender -b --factory-startup --python tools/blender/lamps.py -- OUT.gltf OUT.exr SIZE SPP
# The exported file keeps Principled (base 0.8, roughness 1, specular 0); Cycles renders the floor
# with a pure Diffuse BSDF of the same colour (vkpath's test gives the glTF material
# KHR_materials_specular 0, the same Lambertian BRDF). Lamps are points (radius 0) and the sun a
# direction (angle 0), as glTF's punctual lights are; black world; no denoising.
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

mat = diffuse_floor(20.0, 0.8)


def lamp(name, kind, energy, location, rotation=(0.0, 0.0, 0.0), **props):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    for k, v in props.items():
        setattr(data, k, v)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = rotation
    scene.collection.objects.link(obj)
    return obj


# Blender is +Z up; the exporter turns it to glTF's +Y up.
lamp("point", "POINT", 60.0, (-3.0, 2.0, 2.0), shadow_soft_size=0.0)
lamp("spot", "SPOT", 400.0, (3.0, -1.0, 3.0), (math.radians(15.0), 0.0, 0.0), shadow_soft_size=0.0,
     spot_size=math.radians(50.0), spot_blend=0.3)
lamp("sun", "SUN", 0.5, (0.0, 0.0, 10.0), (math.radians(35.0), 0.0, math.radians(20.0)), angle=0.0)

camera_down(scene, 9.0, 60.0)  # straight down at the floor
world_color(scene, (0.0, 0.0, 0.0))
image_size(scene, size)  # before the export: the camera's aspectRatio
bpy.ops.export_scene.gltf(filepath=out_gltf, export_format="GLTF_SEPARATE", export_lights=True, export_cameras=True)

# Cycles renders the floor as a pure Diffuse BSDF (what vkpath renders with specular 0).
render_as_diffuse(mat, 0.8)

render_cycles(scene, spp, out_exr)
