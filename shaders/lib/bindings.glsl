// Descriptor bindings and data fetches of the path-tracing kernel. Binding numbers:
// shared/kernel_interface.h (the host's descriptor types: host/render/kernel_bindings.cpp);
// specialization constants: lib/spec_constants.glsl.
#ifndef VKP_BINDINGS_GLSL
#define VKP_BINDINGS_GLSL
#include "shared/gpu_types.h"
#include "shared/kernel_interface.h"
#include "shared/microfacet.h"
#include "lib/spec_constants.glsl"

// The shared code compiles out what a scene does not have (plain `if`s on these): primitive kinds
// (shared/intersect.h), material types and shading normals (shared/bsdf.h).
#define VKP_HAS_SPHERES HAS_SPHERES
#define VKP_HAS_QUADS HAS_QUADS
#define VKP_HAS_TRIANGLES HAS_TRIANGLES
#define VKP_HAS_MATERIAL(t) (((MATERIALS >> (t)) & 1u) != 0u)
#define VKP_SHADING_NORMALS HAS_VERTEX_ATTRIBUTES
#define VKP_HAS_LAYERS HAS_LAYERS
#include "shared/intersect.h"  // after the kinds it compiles out

layout(set = 0, binding = VKP_BINDING_FRAME, std140) uniform FrameBlock { GpuFrame frame; };
/// The scale of the ray offset's absolute floor for this scene (shared/ray_offset.h rayOffsetScale).
float sceneOffsetScale() { return frame.origin.w; }
layout(set = 0, binding = VKP_BINDING_NODES) uniform usamplerBuffer uNodes;
layout(set = 0, binding = VKP_BINDING_PRIMS) uniform usamplerBuffer uPrims;
layout(set = 0, binding = VKP_BINDING_MATERIALS) uniform usamplerBuffer uMaterials;
layout(set = 0, binding = VKP_BINDING_LIGHTS) uniform usamplerBuffer uLights;
// Per pixel i: [2i] = running sum (hi), [2i+1] = its compensation (lo), shared/compensated_sum.h.
// accumSum: RGB = sum of samples, w = number of finite samples; accumSq: RGB = sum of squares.
layout(set = 0, binding = VKP_BINDING_ACCUM_SUM, std430) buffer AccumSum { vec4 accumSum[]; };
layout(set = 0, binding = VKP_BINDING_ACCUM_SQ, std430) buffer AccumSq { vec4 accumSq[]; };
layout(set = 0, binding = VKP_BINDING_COUNTERS, std430) buffer Counters { uint counters[]; };
layout(set = 0, binding = VKP_BINDING_ENV_TEXELS) uniform usamplerBuffer uEnvTexels;  // rgb radiance per map texel (bits)
layout(set = 0, binding = VKP_BINDING_ENV_DIST) uniform samplerBuffer uEnvDist;      // R32F: shared/distribution.h table
// Adaptive sampling (host/render/adaptive.h): [2i], [2i+1] = pixel i's decision-stream sums.
layout(set = 0, binding = VKP_BINDING_DECISION, std430) buffer DecisionSums { vec4 decisionSums[]; };
layout(set = 0, binding = VKP_BINDING_ACTIVE, std430) readonly buffer ActivePixels { uint activePixels[]; };
// Feature images (HAS_AOV): AOV_VEC4_PER_PIXEL vec4 of sums per pixel of the band (shared/aov.h).
layout(set = 0, binding = VKP_BINDING_AOV, std430) buffer AovSums { vec4 aovSums[]; };
// Vertex attributes and textures (lib/surface.glsl; layouts: host/render/texture_pack.h).
layout(set = 0, binding = VKP_BINDING_ATTRIBUTES) uniform usamplerBuffer uAttributes;
layout(set = 0, binding = VKP_BINDING_TEX_INFO) uniform usamplerBuffer uTexInfo;
layout(set = 0, binding = VKP_BINDING_TEXELS) uniform usamplerBuffer uTexels;
layout(push_constant) uniform PushBlock { GpuPush push; };

vec4 fetchF(usamplerBuffer b, int i) { return uintBitsToFloat(texelFetch(b, i)); }

GpuNode fetchNode(uint i) {
    int base = int(i * GPU_NODE_TEXELS);
    GpuNode n;
    n.a = fetchF(uNodes, base);
    n.b = fetchF(uNodes, base + 1);
    n.c = fetchF(uNodes, base + 2);
    n.d = fetchF(uNodes, base + 3);
    return n;
}

// ---- Motion blur (HAS_MOTION): every primitive is fetched where it is at the path's time, so the
// traversal, the shading point, light sampling and light pdfs all see one static scene per path.
layout(set = 0, binding = VKP_BINDING_MOTION) uniform usamplerBuffer uMotion;  // GpuMotion per primitive
/// The time of the path in flight, in [0,1) (pathtrace.comp startPath draws it; 0 without motion).
float gTime = 0.0f;

/// No primitive: a scattering point inside a medium (lib/media.glsl; media do not move).
const uint VKP_NO_PRIM = 0xffffffffu;

/// How far primitive i has moved at the path's time gTime (world units): gTime x GpuMotion::v;
/// 0 in variants without motion.
vec3 motionShift(uint i) {
    if (!HAS_MOTION) return vec3(0.0f);
    vec4 v = fetchF(uMotion, int(i * GPU_MOTION_TEXELS));
    return gTime * vec3(v.x, v.y, v.z);
}

/// Primitive i where it is at the path's time (shared/intersect.h primMoved under HAS_MOTION).
GpuPrim fetchPrim(uint i) {
    int base = int(i * GPU_PRIM_TEXELS);
    GpuPrim p;
    p.p0 = fetchF(uPrims, base);
    p.p1 = fetchF(uPrims, base + 1);
    p.p2 = fetchF(uPrims, base + 2);
    if (HAS_MOTION) p = primMoved(p, motionShift(i));
    return p;
}

GpuMaterial fetchMaterial(uint i) {
    int base = int(i * GPU_MATERIAL_TEXELS);
    GpuMaterial m;
    m.m0 = fetchF(uMaterials, base);
    m.m1 = fetchF(uMaterials, base + 1);
    m.m2 = vec4(0.0f);
    m.m3 = vec4(0.0f);
    m.m4 = vec4(0.0f);
    m.m5 = vec4(0.0f);
    // m2: MAT_PBR's specular, an absorbing dielectric's coefficient, JSON texture nodes; other
    // variants skip the fetch.
    if (HAS_PBR || HAS_ABSORPTION || HAS_SOLID_TEXTURES) m.m2 = fetchF(uMaterials, base + 2);
    if (HAS_PBR) {  // only MAT_PBR reads the rest
        m.m3 = fetchF(uMaterials, base + 3);
        if (HAS_LAYERS && (floatBitsToUint(m.m0.w) & MATF_LAYERED) != 0u) {
            m.m4 = fetchF(uMaterials, base + 4);
            m.m5 = fetchF(uMaterials, base + 5);
        }
    }
    return m;
}

/// shared/microfacet.h's table access: the GGX albedo table follows the materials in their texel
/// buffer (host/render/ggx_albedo_table.cpp), at texel frame.counts.w.
vec4 ggxAlbedoFetch(uint t) { return fetchF(uMaterials, int(frame.counts.w + t)); }
/// shared/layers.h's table access: the sheen albedo table follows the GGX table (variants with
/// LAYER_SHEEN; host/render/sheen_albedo_table.cpp).
vec4 sheenAlbedoFetch(uint t) { return fetchF(uMaterials, int(frame.counts.w + GGX_ALBEDO_N * GGX_ALBEDO_N + t)); }

GpuLight fetchLight(uint i) {
    GpuLight l;
    l.l0 = fetchF(uLights, int(i));
    return l;
}
/// Texel of punctual light k's record: after the pick's entries (the sampled objects', counts.x,
/// then the punctual lights', punctual.x).
int punctualTexel(uint k) { return int(frame.counts.x + frame.punctual.x + k * GPU_PUNCTUAL_TEXELS); }
/// Punctual light k's record.
GpuPunctualLight fetchPunctual(uint k) {
    int at = punctualTexel(k);
    GpuPunctualLight l;
    l.q0 = fetchF(uLights, at);
    l.q1 = fetchF(uLights, at + 1);
    l.q2 = fetchF(uLights, at + 2);
    l.q3 = fetchF(uLights, at + 3);
    return l;
}

// ---- Instances (two-level BVH, shared/instance.h): compiled in only for scenes that have some.
// The traversal (lib/traverse_wide.glsl) tests VKP_HAS_INSTANCES.
#define VKP_HAS_INSTANCES HAS_INSTANCES
#include "shared/instance.h"
layout(set = 0, binding = VKP_BINDING_INSTANCES) uniform usamplerBuffer uInstances;  // GPU_INSTANCE_TEXELS per instance

GpuInstance fetchInstance(uint i) {
    int base = int(i * GPU_INSTANCE_TEXELS);
    GpuInstance g;
    g.info = texelFetch(uInstances, base);
    g.w2o0 = fetchF(uInstances, base + 1);
    g.w2o1 = fetchF(uInstances, base + 2);
    g.w2o2 = fetchF(uInstances, base + 3);
    g.o2w0 = fetchF(uInstances, base + 4);
    g.o2w1 = fetchF(uInstances, base + 5);
    g.o2w2 = fetchF(uInstances, base + 6);
    return g;
}

#endif
