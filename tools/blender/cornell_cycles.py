# Renders the classic Cornell box with Cycles, timed by Cycles' own render call: the other side of
# the benchmark suite's "time to Cycles' error" (tools/bench/cycles.py, docs/performance.md).
#
# The scene is scenes/blender-cornell-classic/cornell-rtiow.gltf, the box that Blender's own glTF
# exporter wrote (its README.md), imported as it is and made the twin of scenes/cornell-classic.json:
# every wall and box a pure Diffuse BSDF of the glTF's base colour (the JSON scene's Lambertian
# albedos), the light an Emission of strength 15 on its front face only (the glTF's single-sided
# emitter, vkpath's diffuse_light) and black behind. Cycles' settings that would change the image
# away from the unbiased one are off: denoising, adaptive sampling, sample clamping (3.4 clamps
# indirect samples at 10 by default). The pixel filter is a 1-pixel box, as vkpath's uniform
# samples within the pixel; 50 bounces, as the JSON scene's max_depth. Everything else is Cycles'
# default (its sampler, Russian roulette, light sampling).
#
# Usage: blender -b --factory-startup --python-exit-code 1 --python tools/blender/cornell_cycles.py --
#            GLTF OUT.pfm SIZE SPP SEED THREADS [MAX_BOUNCES [DROP_PREFIX]]
# MAX_BOUNCES (default 50; 0: direct light only) and DROP_PREFIX (objects whose names start with it
# are removed, e.g. box_ for the empty room of tools/bench/room_direct.py) serve the accuracy check
# of docs/accuracy.md "Against Cycles: the Cornell box's walls".
# writes OUT.pfm (linear RGB, float32, rows bottom to top, as vkpath writes PFM) and OUT.json
# {"seconds_render": the render call's wall time, "spp", "seed", "threads", "size", "blender"}.
import json
import os
import sys
import time

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import cycles_settings, image_size, render_as_diffuse, world_color  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
gltf, out_pfm, size, spp, seed, threads = args[0], args[1], int(args[2]), int(args[3]), int(args[4]), int(args[5])
max_bounces = int(args[6]) if len(args) > 6 else 50
drop_prefix = args[7] if len(args) > 7 else None

# Debian 12's Blender 3.4 glTF importer still names np.bool, which Debian's numpy 1.24 removed.
if tuple(int(v) for v in np.__version__.split(".")[:2]) >= (1, 24):
    np.bool = bool
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=gltf)
scene = bpy.context.scene
cameras = [o for o in scene.objects if o.type == "CAMERA"]
if len(cameras) != 1:
    raise SystemExit("cornell_cycles: %s has %d cameras, expected 1" % (gltf, len(cameras)))
scene.camera = cameras[0]
if drop_prefix:
    for o in [o for o in scene.objects if o.name.startswith(drop_prefix)]:
        print("cornell_cycles: removed %s" % o.name)
        bpy.data.objects.remove(o, do_unlink=True)

world_color(scene, (0.0, 0.0, 0.0))

for mat in bpy.data.materials:
    if not mat.use_nodes:
        continue
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    principled = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
    if principled is None or output is None:
        raise SystemExit("cornell_cycles: material %s has no Principled BSDF or output" % mat.name)
    strength = principled.inputs["Emission Strength"].default_value
    emission = principled.inputs["Emission"].default_value
    if strength > 0.0 and max(emission[:3]) > 0.0:
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = emission
        emit.inputs["Strength"].default_value = strength
        black = nodes.new("ShaderNodeBsdfDiffuse")
        black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        facing = nodes.new("ShaderNodeNewGeometry")
        mix = nodes.new("ShaderNodeMixShader")
        links.new(facing.outputs["Backfacing"], mix.inputs["Fac"])
        links.new(emit.outputs["Emission"], mix.inputs[1])
        links.new(black.outputs["BSDF"], mix.inputs[2])
        links.new(mix.outputs["Shader"], output.inputs["Surface"])
        print("cornell_cycles: %s: one-sided emission of strength %g" % (mat.name, strength))
    else:
        base = principled.inputs["Base Color"].default_value
        render_as_diffuse(mat, base)
        print("cornell_cycles: %s: Diffuse BSDF %s" % (mat.name, tuple(round(c, 4) for c in base[:3])))

image_size(scene, size)
exr = out_pfm + ".exr"
cycles_settings(scene, spp, exr, max_bounces=max_bounces, seed=seed)
scene.cycles.diffuse_bounces = max_bounces
scene.cycles.sample_clamp_direct = 0.0
scene.cycles.sample_clamp_indirect = 0.0
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0
scene.render.threads_mode = "FIXED"
scene.render.threads = threads

t0 = time.perf_counter()
bpy.ops.render.render(write_still=False)
seconds = time.perf_counter() - t0
bpy.data.images["Render Result"].save_render(exr)

img = bpy.data.images.load(exr)
img.colorspace_settings.name = "Non-Color"  # the EXR's linear values as they are
px = np.empty(size * size * 4, np.float32)
img.pixels.foreach_get(px)
rgb = px.reshape(size, size, 4)[:, :, :3]  # Blender's rows run bottom to top, as PFM's do
tmp = out_pfm + ".tmp"
with open(tmp, "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (size, size))
    f.write(np.ascontiguousarray(rgb, "<f4").tobytes())
os.replace(tmp, out_pfm)
os.remove(exr)
with open(os.path.splitext(out_pfm)[0] + ".json", "w") as f:
    json.dump({"seconds_render": seconds, "spp": spp, "seed": seed, "threads": threads, "size": size,
               "blender": bpy.app.version_string}, f)
print("cornell_cycles: %d x %d, %d spp, seed %d, %d threads: %.3f s" % (size, size, spp, seed, threads, seconds))
