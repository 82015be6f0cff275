# Reads vkpath's EXR with feature layers (`--aov`, docs/design.md "Feature images") the way a
# compositing user does: Blender's compositor loads it as a multilayer image, and each pass leaves
# through the Composite node to an EXR of its own, which is then compared, pixel for pixel, with the
# file vkpath wrote beside it for that layer (OUT.<layer>.pfm from `-o OUT.pfm`). Every value must
# be the same float: the compositor only moves the data. Run by tools/blender-aov-check.sh:
#   blender -b --factory-startup --python-exit-code 1 --python tools/blender/aov_compositor.py -- \
#           EXR PFM_PREFIX SCRATCH_DIR LAYER[,LAYER...]
# PFM_PREFIX.pfm is the colour image (Blender's "Combined" pass), PFM_PREFIX.<layer>.pfm each layer.
# Prints one line per pass; raises (exit code 1) when a pass is missing, differs, or is all zero.
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import pfm  # noqa: E402  (the benchmark harness's PFM reader: rows top first)

argv = sys.argv[sys.argv.index("--") + 1:]
exr, prefix, scratch, layers = argv[0], argv[1], argv[2], argv[3].split(",")

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
for name, path in passes:
    if name not in names:
        raise RuntimeError("aov_compositor: Blender sees no pass '%s' in %s (it sees %s)" % (name, exr, names))
    expected = pfm.read_pfm(path)
    height, width = expected.shape[:2]
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    for link in list(tree.links):
        tree.links.remove(link)
    tree.links.new(source.outputs[name], composite.inputs["Image"])
    scene.render.filepath = os.path.join(scratch, "blender-%s.exr" % name)
    bpy.ops.render.render(write_still=True)
    result = bpy.data.images.load(scene.render.filepath)
    if tuple(result.size) != (width, height):
        raise RuntimeError("aov_compositor: pass %s is %s in Blender, %dx%d in %s" % (name, tuple(result.size), width, height, path))
    # Blender's pixels: RGBA, bottom row first; a one-channel pass (depth, spp) in each of R, G, B.
    got = np.array(result.pixels[:], dtype=np.float32).reshape(height, width, 4)[::-1, :, :3]
    differ = ~((got == expected) | (np.isnan(got) & np.isnan(expected)))
    for y, x, c in np.argwhere(differ)[:3]:
        print("aov_compositor: %s pixel (%d, %d) channel %d: Blender %r, vkpath %r" % (name, x, y, c, got[y, x, c], expected[y, x, c]))
    print("aov_compositor: pass %s (%dx%d): %d values differ" % (name, width, height, np.count_nonzero(differ)))
    if differ.any():
        raise RuntimeError("aov_compositor: pass %s differs from %s in %d values" % (name, path, np.count_nonzero(differ)))
    if not np.count_nonzero(expected):
        raise RuntimeError("aov_compositor: pass %s is all zero: nothing was compared" % name)
print("aov_compositor: %d passes read through Blender's compositor, every value as vkpath wrote it" % len(passes))
