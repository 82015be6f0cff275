# What tools/blender/*.py share (Debian's Blender 3.4): a camera looking straight down, a world of
# one colour, the image size (set before the glTF export, which writes the camera's aspect ratio),
# and Cycles' settings for a reference render (CPU, fixed seed, no denoising, no adaptive sampling,
# linear 32-bit EXR).
import math

import bpy


def camera_down(scene, height, angle_degrees):
    """A camera at (0, 0, height) (Blender's +Z up) looking down -Z with the given field of view."""
    data = bpy.data.cameras.new("camera")
    data.angle = math.radians(angle_degrees)
    cam = bpy.data.objects.new("camera", data)
    cam.location = (0.0, 0.0, height)
    scene.collection.objects.link(cam)
    scene.camera = cam


def world_color(scene, rgb):
    """A world of constant radiance rgb (no nodes)."""
    world = bpy.data.worlds.new("world")
    world.use_nodes = False
    world.color = rgb
    scene.world = world


def image_size(scene, size):
    scene.render.resolution_x = size
    scene.render.resolution_y = size
    scene.render.resolution_percentage = 100


def cycles_settings(scene, spp, out_exr, max_bounces=None, seed=1):
    """Cycles' settings for a reference render of scene to the linear EXR out_exr (not rendered)."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = spp
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = seed
    if max_bounces is not None:
        scene.cycles.max_bounces = max_bounces
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = out_exr


def render_cycles(scene, spp, out_exr, max_bounces=None):
    """Cycles' reference render of scene to the linear EXR out_exr."""
    cycles_settings(scene, spp, out_exr, max_bounces)
    bpy.ops.render.render(write_still=True)


def diffuse_floor(size, albedo):
    """A size x size floor at z = 0 whose Principled material (base albedo, roughness 1, specular 0,
    not metallic) the exporter writes; returns that material."""
    bpy.ops.mesh.primitive_plane_add(size=size, location=(0.0, 0.0, 0.0))
    floor = bpy.context.active_object
    mat = bpy.data.materials.new("floor")
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (albedo, albedo, albedo, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.0
    bsdf.inputs["Metallic"].default_value = 0.0
    floor.data.materials.append(mat)
    return mat


def render_as_diffuse(mat, albedo):
    """After the export: Cycles renders mat as a pure Diffuse BSDF of that albedo (a grey level or
    linear RGB; the Lambertian BRDF vkpath renders with specular 0)."""
    nodes = mat.node_tree.nodes
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    rgb = tuple(albedo[:3]) if hasattr(albedo, "__len__") else (albedo, albedo, albedo)
    diffuse.inputs["Color"].default_value = rgb + (1.0,)
    diffuse.inputs["Roughness"].default_value = 0.0
    mat.node_tree.links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
