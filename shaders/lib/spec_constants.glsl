// Every specialization constant of the path-tracing kernel, in id order (ids: shared/kernel_interface.h;
// the host's values: host/render/features.cpp, Features::specTable). A false constant removes the
// code it guards from the pipeline, which on lavapipe is the only way to make it free
// (docs/design.md). The defaults are the `full` variant: everything compiled in.
#ifndef VKP_SPEC_CONSTANTS_GLSL
#define VKP_SPEC_CONSTANTS_GLSL
#include "shared/kernel_interface.h"
#include "shared/kinds.h"

layout(constant_id = VKP_SPEC_SHAPES) const uint SHAPES = 0xffffffffu;        // bit PRIM_* per kind in the BVH
layout(constant_id = VKP_SPEC_MATERIALS) const uint MATERIALS = 0xffffffffu;  // bit MAT_* per type used
layout(constant_id = VKP_SPEC_HAS_EMITTERS) const bool HAS_EMITTERS = true;
layout(constant_id = VKP_SPEC_LIGHTS) const uint LIGHTS = 0xffffffffu;        // bit PRIM_* per kind in the light list, LIGHT_KIND_PUNCTUAL
layout(constant_id = VKP_SPEC_SAMPLER) const uint SAMPLER = 2u;               // SAMPLER_* (shared/kinds.h)
layout(constant_id = VKP_SPEC_SEQUENCE) const uint SEQUENCE = 1u;             // SEQUENCE_* (shared/sample_stream.h)
// Next-event estimation samples quads and triangles in solid angle (else in area) from points
// where the light's apparent size (area / squared distance to its centre, sr) is at least
// SOLID_ANGLE_MIN_SIZE (shared/rect_sampling.h apparentSize; 0: everywhere).
layout(constant_id = VKP_SPEC_SOLID_ANGLE_LIGHTS) const bool SOLID_ANGLE_LIGHTS = true;
layout(constant_id = VKP_SPEC_SOLID_ANGLE_MIN_SIZE) const float SOLID_ANGLE_MIN_SIZE = 0.0f;
layout(constant_id = VKP_SPEC_HAS_DEFOCUS) const bool HAS_DEFOCUS = true;
layout(constant_id = VKP_SPEC_HAS_ENV) const bool HAS_ENV = true;          // escaping rays see radiance (lib/environment.glsl)
layout(constant_id = VKP_SPEC_HAS_ENV_MAP) const bool HAS_ENV_MAP = true;  // ... from a map (else the constant background)
layout(constant_id = VKP_SPEC_HAS_VERTEX_ATTRIBUTES) const bool HAS_VERTEX_ATTRIBUTES = true;  // lib/surface.glsl
layout(constant_id = VKP_SPEC_HAS_TEXTURES) const bool HAS_TEXTURES = true;
// ... and some MAT_PBR material reads a KHR_materials_specular texture (specularTexture,
// specularColorTexture) or a KHR_materials_transmission transmissionTexture: their three lookups
// run at every PBR hit of a variant that has them.
layout(constant_id = VKP_SPEC_HAS_EXTENSION_TEXTURES) const bool HAS_EXTENSION_TEXTURES = true;
// ... and some texture slot reads TEXCOORD_1: its UVs are fetched at every textured hit.
layout(constant_id = VKP_SPEC_HAS_TEXCOORD1) const bool HAS_TEXCOORD1 = true;
layout(constant_id = VKP_SPEC_HAS_ALPHA) const bool HAS_ALPHA = true;          // lib/alpha.glsl
layout(constant_id = VKP_SPEC_HAS_INSTANCES) const bool HAS_INSTANCES = true;  // shared/instance.h
layout(constant_id = VKP_SPEC_HAS_VERTEX_COLORS) const bool HAS_VERTEX_COLORS = true;  // COLOR_0 (lib/surface.glsl)
// Clear coat and sheen over the glTF BRDF (LAYER_* bits; shared/layers.h): their material texels,
// textures, coat normal and lobes run only in variants with some.
layout(constant_id = VKP_SPEC_LAYERS) const uint LAYERS = 0xffffffffu;
// Some dielectric absorbs the light inside it (Beer-Lambert; GpuMaterial m2.xyz): paths carry
// the absorption coefficient of the glass they travel in.
layout(constant_id = VKP_SPEC_HAS_ABSORPTION) const bool HAS_ABSORPTION = true;
// Some lambertian, metal or diffuse_light material takes its albedo or emission from a JSON
// texture (checker, image, Perlin noise: shared/solid_texture.h, lib/solid_texture.glsl).
layout(constant_id = VKP_SPEC_HAS_SOLID_TEXTURES) const bool HAS_SOLID_TEXTURES = true;
// Some primitive moves over the shutter interval (motion blur, "Ray Tracing: The Next Week" sec. 2):
// each path draws a time (shared/sample_stream.h sampleTime) and every primitive is fetched moved
// to it (lib/bindings.glsl fetchPrim, GpuMotion).
layout(constant_id = VKP_SPEC_HAS_MOTION) const bool HAS_MOTION = true;
// Feature images (`--aov`, shared/aov.h): every sample adds the albedo and normal of its first
// non-specular vertex and the position of its first hit to the pixel's AOV sums.
layout(constant_id = VKP_SPEC_HAS_AOV) const bool HAS_AOV = true;
// An invocation may trace the samples of several pixels, one after the other (push.batch.z
// slots): the path that ends a pixel's samples is followed by the next pixel's first, so lanes stay
// busy when a dispatch adds few samples per pixel (a large image; host/render/renderer.cpp). The
// switch from one pixel's sums to the next's would otherwise run, masked, in every pass.
layout(constant_id = VKP_SPEC_PIXEL_SLOTS) const bool PIXEL_SLOTS = true;
// Workgroup size: 8x8 by default (`--workgroup`), one pixel per invocation.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1, local_size_x_id = VKP_SPEC_WORKGROUP_X,
       local_size_y_id = VKP_SPEC_WORKGROUP_Y) in;

// ---- Derived: what the masks above compile in (specialization-constant expressions, folded when
// the pipeline is created, so a false one removes its code as a plain constant does).
const bool HAS_SPHERES = (SHAPES & (1u << PRIM_SPHERE)) != 0u;
const bool HAS_QUADS = (SHAPES & (1u << PRIM_QUAD)) != 0u;
const bool HAS_TRIANGLES = (SHAPES & (1u << PRIM_TRIANGLE)) != 0u;
const bool HAS_LAMBERTIAN = (MATERIALS & (1u << MAT_LAMBERTIAN)) != 0u;
const bool HAS_METAL = (MATERIALS & (1u << MAT_METAL)) != 0u;
const bool HAS_DIELECTRIC = (MATERIALS & (1u << MAT_DIELECTRIC)) != 0u;
const bool HAS_PBR = (MATERIALS & (1u << MAT_PBR)) != 0u;  // glTF metallic-roughness materials
// Constant-density media (lib/media.glsl): their phase function is the material type MAT_ISOTROPIC.
const bool HAS_MEDIA = (MATERIALS & (1u << MAT_ISOTROPIC)) != 0u;
// Kinds in the light list, compiled apart: on lavapipe every compiled-in light kind's sampling code
// runs at every vertex (docs/design.md).
const bool HAS_SPHERE_LIGHTS = (LIGHTS & (1u << PRIM_SPHERE)) != 0u;
const bool HAS_QUAD_LIGHTS = (LIGHTS & (1u << PRIM_QUAD)) != 0u;
const bool HAS_TRIANGLE_LIGHTS = (LIGHTS & (1u << PRIM_TRIANGLE)) != 0u;
// Point, spot and directional lights (shared/punctual_light.h): delta lights, sampled by
// next-event estimation under every sampler.
const bool HAS_PUNCTUAL_LIGHTS = (LIGHTS & (1u << LIGHT_KIND_PUNCTUAL)) != 0u;
// Layers count only with MAT_PBR (integer arithmetic: glslang turns && of specialization
// constants into control flow, which is not a constant expression).
const uint LAYERS_USED = LAYERS & (LAYER_COAT | LAYER_SHEEN) & (0u - ((MATERIALS >> MAT_PBR) & 1u));
const bool HAS_COAT = (LAYERS_USED & LAYER_COAT) != 0u;
const bool HAS_SHEEN = (LAYERS_USED & LAYER_SHEEN) != 0u;
const bool HAS_LAYERS = LAYERS_USED != 0u;
// Something for the power-proportional pick: an emitting surface or a punctual light.
const bool HAS_PICKED_LIGHTS = HAS_EMITTERS || HAS_PUNCTUAL_LIGHTS;

#endif
