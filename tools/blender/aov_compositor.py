# Reads vkpath's EXR with feature layers (`--aov`, docs/design.md "Feature images") the way a
# compositing user does: Blender's compositor loads it as a multilayer image, and each pass leaves
# through the Composite node to an EXR of its own, which is then compared, pixel for pixel, with the
# file vkpath wrote beside it for that layer (OUT.<layer>.pfm from `-o OUT.pfm`). Every value must
# be the same float: the compositor only moves the data. Run by tools/blender-aov-check.sh:
#   blender -b --factory-startup --python-exit-code 1 --python tools/blender/aov_compositor.py -- \
#           EXR PFM_PREFIX SCRATCH_DIR LAYER[,LAYER...]
# PFM_PREFIX.pfm is the colour image (Blender's "Combined" pass), PFM_PREFIX.<layer>.pfm each layer.
# Prints one line per pass; raises (exit code 1) when a pass is missing, differs, or is all zero.
import math
import os
import struct
import sys

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
exr, prefix, scratch, layers = argv[0], argv[1], argv[2], argv[3].split(",")


def read_pfm(path):
    """(width, height, channels, floats bottom row first), as the PFM stores them."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        count = width * height * channels
        data = struct.unpack(("<" if scale < 0 else ">") + "%df" % count, f.read(4 * count))
    return width, height, channels, data


def same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


image = bpy.data.images.load(exr)
scene = bpy.context.scene
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)
source = tree.nodes.new("CompositorNodeImage")
source.image = image
composite = tree.nodes.new("CompositorNodeComposite")
composite.use_alpha = False
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.view_settings.view_transform = "Standard"  # EXR output is linear anyway; no look either
passes = [("Combined", prefix + ".pfm")] + [(layer, "%s.%s.pfm" % (prefix, layer)) for layer in layers]
names = [o.name for o in source.outputs]
for name, pfm in passes:
    if name not in names:
        raise RuntimeError("aov_compositor: Blender sees no pass '%s' in %s (it sees %s)" % (name, exr, names))
    width, height, channels, expected = read_pfm(pfm)
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    for link in list(tree.links):
        tree.links.remove(link)
    tree.links.new(source.outputs[name], composite.inputs["Image"])
    scene.render.filepath = os.path.join(scratch, "blender-%s.exr" % name)
    bpy.ops.render.render(write_still=True)
    result = bpy.data.images.load(scene.render.filepath)
    if tuple(result.size) != (width, height):
        raise RuntimeError("aov_compositor: pass %s is %s in Blender, %dx%d in %s" % (name, tuple(result.size), width, height, pfm))
    got = result.pixels[:]  # RGBA, bottom row first, as the PFM
    differing = 0
    nonzero = 0
    for i in range(width * height):
        for c in range(3):
            want = expected[i * channels + (c if channels == 3 else 0)]
            nonzero += want != 0.0
            if not same(got[4 * i + c], want):
                if differing < 3:
                    print("aov_compositor: %s pixel %d channel %d: Blender %r, vkpath %r" % (name, i, c, got[4 * i + c], want))
                differing += 1
    print("aov_compositor: pass %s (%dx%d, %d channel%s): %d values differ" %
          (name, width, height, channels, "s" if channels > 1 else "", differing))
    if differing:
        raise RuntimeError("aov_compositor: pass %s differs from %s in %d values" % (name, pfm, differing))
    if not nonzero:
        raise RuntimeError("aov_compositor: pass %s is all zero: nothing was compared" % name)
print("aov_compositor: %d passes read through Blender's compositor, every value as vkpath wrote it" % len(passes))
