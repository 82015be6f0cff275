// GPU data layout: the one declaration of every struct the host uploads and the kernels read.
// Included by C++ (host/, static_asserts in host/render/gpu_layout_check.cpp) and by GLSL.
// Large arrays live in texel buffers (RGBA32UI, one texel = one vec4/uvec4 member); the small
// per-frame block is a uniform buffer (std140). See docs/design.md for why. The kinds and flags
// stored in these structs (PRIM_*, MAT_*, MATF_*) are defined in shared/kinds.h.
#ifndef VKP_GPU_TYPES_H
#define VKP_GPU_TYPES_H
#include "glsl_compat.h"
#include "kinds.h"

VKP_BEGIN

// ---- Primitives (3 texels, 48 bytes) --------------------------------------------------------
// Header word (p0.w as bits): kind (PRIM_*) | (material << 2). Material indices < 2^30. PRIM_INSTANCE:
// kind | (instance index << 2), every coordinate NaN (shared/instance.h).
// p0.xyz: sphere centre | quad Q | triangle v0        (world units)
// p1.xyz: -             | quad u | triangle v1; p1.w: sphere radius | 0 | triangle: 1 if of zero area
//         (intersect.h triangleHasZeroArea: never hit), else 0
// p2.xyz: -             | quad v | triangle v2; p2.w: bits of light index + 1 (0: not a light)
// Triangles keep their vertices, not edges: v0 + (v1 - v0) != v1 in float, and neighbours must see
// bit-identical shared vertices for the watertight test (intersect.h). primEdge1/2 give the edges.
struct GpuPrim {
    vec4 p0;
    vec4 p1;
    vec4 p2;
};
const uint GPU_PRIM_TEXELS = 3u;

// ---- Motion (1 texel per primitive, in the order of the primitives) ---------------------------
// Motion blur ("Ray Tracing: The Next Week", sec. 2). v.xyz: the primitive's displacement over
// the shutter interval (world units): at time t in [0,1) the primitive is its GpuPrim moved by
// t v.xyz (shared/intersect.h primMoved: a sphere's centre, a quad's Q, all three vertices of a
// triangle), so a sphere's centre goes from `center` at t = 0 towards `center1` at t = 1; v.w: 0.
// Read only by variants with HAS_MOTION (lib/bindings.glsl fetchPrim); the others upload one token
// texel. Instances and the triangles of instanced meshes never move (v = 0).
struct GpuMotion {
    vec4 v;
};
const uint GPU_MOTION_TEXELS = 1u;

// ---- BVH nodes (4 texels, 64 bytes): a binary node stores the boxes of both children ---------
// FlatBvh::nodes: the build intermediate the 4-wide nodes the kernels traverse are collapsed from
// (shared/wide_bvh.h); only the layout benchmark's test kernel traverses these
// (shaders/tests/traverse_binary.glsl).
// a.xyz/b.xyz: left child min/max, c.xyz/d.xyz: right child min/max.
// a.w: left child (bits): node index if b.w == 0, else first primitive of the leaf;
// b.w: left leaf primitive count (bits, 0 = inner node); c.w, d.w: the same for the right child.
// An empty child (only in a scene with < 2 primitives) has min = +big, max = -big and count 0
// with index 0xffffffff: it is never entered. Node 0 is the root.
struct GpuNode {
    vec4 a;
    vec4 b;
    vec4 c;
    vec4 d;
};
const uint GPU_NODE_TEXELS = 4u;
const uint GPU_NODE_EMPTY = 0xffffffffu;

// ---- Materials (4 texels) ----------------------------------------------------------------------
// m0.xyz: albedo (linear RGB; pbr: baseColorFactor), m0.w: bits of type (MAT_*) | flags (MATF_*)
// m1.xyz: emitted radiance (linear RGB, W sr^-1 m^-2 in scene units), m1.w: fuzz (metal) or ior
// m2 (pbr): xyz = KHR_materials_specular specularColorFactor, w = specularFactor; (dielectric):
//    xyz = Beer-Lambert absorption inside; (with MATF_SOLID_TEXTURE): x, y = bits of the albedo's
//    and the emission's texture node + 1 (0: the constant in m0 / m1; shared/solid_texture.h)
// m3 (pbr only): x = metallicFactor, y = roughnessFactor, z = KHR_materials_transmission
//    transmissionFactor when a transmissionTexture decides per hit (host transmissionTextured),
//    else 0; w = KHR_materials_ior ior
// The kernel fetches m2 only in variants with MAT_PBR, absorption or JSON textures, and m3 only
// with MAT_PBR (shaders/lib/bindings.glsl).
// m4 (pbr with MATF_LAYERED): x = KHR_materials_clearcoat clearcoatFactor, y =
//    clearcoatRoughnessFactor, z = KHR_materials_sheen sheenRoughnessFactor, w = 0
// m5 (pbr with MATF_LAYERED): xyz = sheenColorFactor (linear RGB), w = 0
// The kernel fetches m4 and m5 only in variants with LAYERS, for materials with MATF_LAYERED.
struct GpuMaterial {
    vec4 m0;
    vec4 m1;
    vec4 m2;
    vec4 m3;
    vec4 m4;
    vec4 m5;
};
const uint GPU_MATERIAL_TEXELS = 6u;

// ---- Sampled objects ("lights", 1 texel) -------------------------------------------------------
// The lights buffer holds, in order: one GpuLight per sampled object (GpuFrame::counts.x of them:
// the book's mixture picks among these), one GpuLight per punctual light (GpuFrame::punctual.x of
// them; the power pick's alias table spans both lists), then one GpuPunctualLight record per
// punctual light, from the entry after the last GpuLight on.
// x: bits of the primitive index, or of LIGHT_PUNCTUAL_BIT | punctual light index; y: probability
// of picking it in proportion to emitted power (0 for an object that does not emit), z:
// alias-table threshold of column i (shared/light_pick.h), w: bits of the alias index of column i.
// The uniform pick of the book has probability 1/count.
struct GpuLight {
    vec4 l0;
};
const uint GPU_LIGHT_TEXELS = 1u;

// ---- Punctual lights (4 texels; shared/punctual_light.h) ---------------------------------------
// q0.xyz: position (point, spot; world units, camera-relative) or the unit direction towards a
//         directional light; q0.w: bits of the kind (PUNCTUAL_*)
// q1.xyz: intensity (W/sr; directional: irradiance, W/m^2), linear RGB; q1.w: the spot's
//         falloff scale (spotScale)
// q2.xyz: the spot's unit axis (the way it points); q2.w: cos(outer cone angle)
// q3: the pick among the punctual lights alone (the `bsdf` and `mixture` samplers, which sample
//     delta lights by next-event estimation only), laid out as a GpuLight entry so that the same
//     alias routines read it (shared/light_pick.h): x = 0, y = its probability, z = alias
//     threshold, w = bits of the alias index
struct GpuPunctualLight {
    vec4 q0;
    vec4 q1;
    vec4 q2;
    vec4 q3;
};
const uint GPU_PUNCTUAL_TEXELS = 4u;

// ---- Per-render uniform block (std140, vec4 members only) -------------------------------------
// Camera of "Ray Tracing in One Weekend" sec. 13: pixel (i,j) centre = pixel00 + i du + j dv,
// where row j = 0 is the top of the image; defocus disk = origin + a du_lens + b dv_lens.
struct GpuFrame {
    vec4 origin;      // xyz: camera centre (world units); w: the ray offset's scale (shared/ray_offset.h
                      // rayOffsetScale of the scene's extent)
    vec4 pixel00;     // xyz: centre of pixel (0,0)
    vec4 pixelDu;     // xyz: step to the next column (+u)
    vec4 pixelDv;     // xyz: step to the next row (-v)
    vec4 defocusU;    // xyz: defocus disk radius along u (0 = pinhole)
    vec4 defocusV;    // xyz: defocus disk radius along v
    vec4 background;  // rgb: radiance of escaping rays
    uvec4 size;       // x: width, y: height, z: max_depth, w: seed
    uvec4 counts;     // x: number of sampled objects (lights), y: Russian-roulette start depth,
                      // z: number of them that emit (power-proportional picks need > 0),
                      // w: texel of the GGX albedo table in the materials buffer (after the materials)
    vec4 env;         // environment light (lib/environment.glsl): x, y: cos, sin of rotate_y;
                      // z: probability that next-event estimation picks the environment instead
                      // of an emitter (host/render/environment.h); w: 1 if escaping rays see
                      // radiance (a map or a non-zero background), else 0
    uvec4 envSize;    // x, y: width, height of the environment map (0: none, the constant
                      // background is the environment); z, w: 0
    uvec4 punctual;   // x: number of punctual lights (shared/punctual_light.h); y, z, w: 0
    uvec4 media;      // x: number of constant-density media (shared/medium.h), y: texel of the
                      // first GpuMedium record in the materials buffer; z, w: 0
};

// Push constants of one dispatch: samples [sampleStart, sampleStart + sampleCount) of every pixel
// of one band of rows (host/render/gpu_arrays.h planBands; the whole image unless its
// accumulation buffers exceed the device's storage-buffer range). With adaptive sampling
// (host/render/adaptive.h) a dispatch covers only the band's active pixels, listed in the
// active-pixel buffer: workgroup g (= y * gl_NumWorkGroups.x + x) takes the entries of slot
// (g * adaptive.z) mod adaptive.y, so lavapipe's per-thread runs of workgroups spread over the band.
struct GpuPush {
    uvec4 batch;     // x: sampleStart, y: sampleCount (per pixel), z: pixels per invocation (>= 1;
                     // > 1 only with PIXEL_SLOTS: workgroup g takes virtual workgroups g * z .. g * z + z - 1),
                     // w: reserved
    uvec4 adaptive;  // x: active pixels listed (0: adaptive sampling off, every pixel of the band),
                     // y: workgroups with work, z: slot stride (coprime with y, y * z < 2^32),
                     // w: reserved (0)
    uvec4 band;      // x: first row, y: rows, z: tiles (workgroups) in the band, w: tile stride
                     // (coprime with z, z * w < 2^32): workgroup g renders tile (g * w) mod z
};

// Accumulation (SSBO, written by the kernel): per pixel, sum.rgb and the number of finite samples
// in sum.w; sumSq.rgb the per-channel sum of squares (for variance estimates); each a double-float
// pair (shaders/lib/bindings.glsl). Decision stream of adaptive sampling (SSBO): per pixel, RGB sum
// and count, then RGB sum of squares, of the samples that only steer (host/render/adaptive.h).
// Counters (SSBO): see COUNTER_* indices.
const uint COUNTER_NONFINITE = 0u;   // samples dropped: NaN, Inf or above MAX_SAMPLE_RADIANCE
// The largest sample a pixel's sums take: 2^24 samples of it still have a finite sum of squares
// (2^24 * (4e15)^2 = 2.7e38 < FLT_MAX = 3.4e38). Larger samples (an emitter or background of 1e38,
// say) are dropped and counted as non-finite, so that no pixel's sums overflow (issue 15, defect 5).
const float MAX_SAMPLE_RADIANCE = 4.0e15f;
const uint COUNTER_RAYS_LO = 1u;     // rays traced (64-bit, low word)
const uint COUNTER_RAYS_HI = 2u;     // rays traced (high word)
const uint COUNTER_LOOP_GUARD = 3u;  // paths cut short by the loop-pass guard (must stay 0)
const uint COUNTER_MAX_PASSES = 4u;  // most loop passes of one invocation in the last submission
const uint COUNTER_COUNT = 5u;

VKP_END
#endif
