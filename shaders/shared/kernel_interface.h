// The interface between the host and the path-tracing kernel (shaders/pathtrace.comp), declared
// once for both languages: the number of every descriptor binding (set 0) and the id of every
// specialization constant.
//   GLSL: shaders/lib/bindings.glsl declares the bindings with these numbers, and
//         shaders/lib/spec_constants.glsl declares every constant_id, in id order.
//   C++:  host/render/kernel_bindings.cpp holds the descriptor type of each binding, and
//         host/render/features.cpp builds the specialization data from one table {id, name, value};
//         both static_assert that they cover VKP_BINDING_COUNT / VKP_SPEC_COUNT entries, in order.
// Plain macros, because GLSL layout qualifiers need integral constant expressions and both
// preprocessors read them. Renumbering is free (nothing outside this file uses the numbers).
#ifndef VKP_KERNEL_INTERFACE_H
#define VKP_KERNEL_INTERFACE_H

// ---- Descriptor bindings of set 0 --------------------------------------------------------------
// Read-only scene data lives in texel buffers and the per-render block in a uniform buffer; only
// what the kernel writes is a storage buffer (docs/design.md, "How data is read decides speed").
#define VKP_BINDING_FRAME 0          // uniform buffer: GpuFrame (shared/gpu_types.h)
#define VKP_BINDING_NODES 1          // texel RGBA32UI: 4-wide BVH nodes (shared/wide_bvh.h)
#define VKP_BINDING_PRIMS 2          // texel RGBA32UI: GpuPrim
#define VKP_BINDING_MATERIALS 3      // texel RGBA32UI: GpuMaterial, then the GGX albedo table
#define VKP_BINDING_LIGHTS 4         // texel RGBA32UI: GpuLight (the light list and its alias table)
#define VKP_BINDING_ACCUM_SUM 5      // storage: per pixel, compensated sum of samples (RGB, count)
#define VKP_BINDING_ACCUM_SQ 6       // storage: per pixel, compensated sum of squares
#define VKP_BINDING_COUNTERS 7       // storage: COUNTER_* (shared/gpu_types.h)
#define VKP_BINDING_ENV_TEXELS 8     // texel RGBA32UI: environment map radiance
#define VKP_BINDING_ENV_DIST 9       // texel R32F: the map's sampling distribution (shared/distribution.h)
#define VKP_BINDING_DECISION 10      // storage: adaptive sampling's decision-stream sums
#define VKP_BINDING_ACTIVE 11        // storage (read-only): adaptive sampling's active pixels
#define VKP_BINDING_ATTRIBUTES 12    // texel RGBA32UI: vertex-attribute records (lib/surface.glsl)
#define VKP_BINDING_TEX_INFO 13      // texel RGBA32UI: texture headers and material texture records
#define VKP_BINDING_TEXELS 14        // texel R32UI: RGBA8 texels of every image
#define VKP_BINDING_INSTANCES 15     // texel RGBA32UI: GpuInstance (shared/instance.h)
#define VKP_BINDING_MOTION 16        // texel RGBA32UI: GpuMotion per primitive (motion blur; a token texel without)
#define VKP_BINDING_AOV 17           // storage: per pixel, sums of the feature images (shared/aov.h; a token without HAS_AOV)
#define VKP_BINDING_COUNT 18

// ---- Specialization constants (shaders/lib/spec_constants.glsl declares them in this order) ----
// The variant of the kernel that a scene needs: a false constant removes the code it guards from
// the pipeline, which on lavapipe is the only way to make it free (docs/design.md).
#define VKP_SPEC_SHAPES 0                  // uint: bit PRIM_* for each primitive kind in the BVH
#define VKP_SPEC_MATERIALS 1               // uint: bit MAT_* for each kernel material type used
#define VKP_SPEC_HAS_EMITTERS 2            // bool: some material emits
#define VKP_SPEC_LIGHTS 3                  // uint: bit PRIM_* for each kind in the light list
#define VKP_SPEC_SAMPLER 4                 // uint: SAMPLER_* (shared/kinds.h)
#define VKP_SPEC_SEQUENCE 5                // uint: SEQUENCE_* (shared/kinds.h)
#define VKP_SPEC_SOLID_ANGLE_LIGHTS 6      // bool: NEE samples quads/triangles in solid angle
#define VKP_SPEC_SOLID_ANGLE_MIN_SIZE 7    // float: ... from this apparent size on (sr; 0: always)
#define VKP_SPEC_HAS_DEFOCUS 8             // bool: a thin-lens camera
#define VKP_SPEC_HAS_ENV 9                 // bool: escaping rays see radiance
#define VKP_SPEC_HAS_ENV_MAP 10            // bool: ... from a map (else the constant background)
#define VKP_SPEC_HAS_VERTEX_ATTRIBUTES 11  // bool: UVs and shading normals of mesh triangles
#define VKP_SPEC_HAS_TEXTURES 12           // bool: materials read textures
#define VKP_SPEC_HAS_EXTENSION_TEXTURES 13 // bool: KHR_materials_specular / _transmission textures
#define VKP_SPEC_HAS_TEXCOORD1 14          // bool: some texture slot reads TEXCOORD_1
#define VKP_SPEC_HAS_ALPHA 15              // bool: some material has alphaMode MASK or BLEND
#define VKP_SPEC_HAS_INSTANCES 16          // bool: a two-level BVH (shared/instance.h)
#define VKP_SPEC_HAS_VERTEX_COLORS 17      // bool: glTF COLOR_0 tints some MAT_PBR material
#define VKP_SPEC_LAYERS 18                 // uint: LAYER_* over some MAT_PBR material (shared/layers.h)
#define VKP_SPEC_WORKGROUP_X 19            // uint: local_size_x (`--workgroup`)
#define VKP_SPEC_WORKGROUP_Y 20            // uint: local_size_y
#define VKP_SPEC_HAS_ABSORPTION 21         // bool: some dielectric absorbs inside (Beer-Lambert)
#define VKP_SPEC_HAS_SOLID_TEXTURES 22     // bool: some material has a JSON texture (shared/solid_texture.h)
#define VKP_SPEC_HAS_MOTION 23             // bool: some primitive moves over the shutter interval (GpuMotion)
#define VKP_SPEC_HAS_AOV 24                // bool: add every sample's feature values to VKP_BINDING_AOV (`--aov`)
#define VKP_SPEC_PIXEL_SLOTS 25           // bool: an invocation may take several pixels (push.batch.z > 1)
#define VKP_SPEC_COUNT 26

#endif
