// Descriptor bindings, specialization constants and data fetches of the path-tracing kernel.
// Binding numbers must match host/render/renderer.cpp (kBinding*).
#ifndef VKP_BINDINGS_GLSL
#define VKP_BINDINGS_GLSL
#include "shared/gpu_types.h"

// ---- Variant: what this scene needs (host/render/features.cpp). A false constant removes the
// code it guards from the pipeline, which on lavapipe is the only way to make it free.
layout(constant_id = 0) const bool HAS_SPHERES = true;
layout(constant_id = 1) const bool HAS_PARALLELOGRAMS = true;  // quads and triangles
layout(constant_id = 2) const bool HAS_LAMBERTIAN = true;
layout(constant_id = 3) const bool HAS_METAL = true;
layout(constant_id = 4) const bool HAS_DIELECTRIC = true;
layout(constant_id = 5) const bool HAS_EMITTERS = true;
layout(constant_id = 6) const bool HAS_SPHERE_LIGHTS = true;         // sampled spheres
layout(constant_id = 7) const bool HAS_QUAD_LIGHTS = true;           // sampled quads
layout(constant_id = 22) const bool HAS_TRIANGLE_LIGHTS = true;      // sampled triangles (apart from quads:
// every compiled-in light kind's sampling code runs at every vertex on lavapipe, DESIGN.md)
layout(constant_id = 8) const uint SAMPLER = 2u;                     // SAMPLER_* below
layout(constant_id = 9) const bool HAS_DEFOCUS = true;
layout(constant_id = 10) const bool HAS_ENV = true;      // escaping rays see radiance (lib/environment.glsl)
layout(constant_id = 11) const bool HAS_ENV_MAP = true;  // ... from a map (else the constant background)
layout(constant_id = 12) const bool HAS_PBR = true;  // glTF metallic-roughness materials (MAT_PBR)
layout(constant_id = 16) const uint SEQUENCE = 1u;   // SEQUENCE_* below (shared/sample_stream.h)
layout(constant_id = 17) const bool SOLID_ANGLE_LIGHTS = true;  // NEE samples quads/triangles in solid angle (else area)
// ... from points where the light's apparent size (area / squared distance to its centre, sr) is at
// least this (shared/rect_sampling.h apparentSize; 0: everywhere; `--light-sampling auto|solid-angle`).
layout(constant_id = 21) const float SOLID_ANGLE_MIN_SIZE = 0.0f;

// intersect.h compiles out the primitive kinds a scene does not have (plain `if`s on these).
#define VKP_HAS_SPHERES HAS_SPHERES
#define VKP_HAS_PARALLELOGRAMS HAS_PARALLELOGRAMS

const uint SAMPLER_BSDF = 0u;     // cosine sampling only; emission counted where rays hit it
const uint SAMPLER_LIGHT = 1u;    // next-event estimation: one light sample + shadow ray per vertex
const uint SAMPLER_MIXTURE = 2u;  // the book: 0.5 cosine + 0.5 lights (uniform pick), one direction
const uint SAMPLER_MIS = 3u;      // light sample + BSDF sample, power heuristic (Veach 1997)

const uint SEQUENCE_RANDOM = 0u;  // independent hashed random numbers per dimension (shared/rng.h)
const uint SEQUENCE_SOBOL = 1u;   // Owen-scrambled Sobol' points, padded (shared/sobol.h)


layout(set = 0, binding = 0, std140) uniform FrameBlock { GpuFrame frame; };
layout(set = 0, binding = 1) uniform usamplerBuffer uNodes;
layout(set = 0, binding = 2) uniform usamplerBuffer uPrims;
layout(set = 0, binding = 3) uniform usamplerBuffer uMaterials;
layout(set = 0, binding = 4) uniform usamplerBuffer uLights;
// Per pixel i: [2i] = running sum (hi), [2i+1] = its compensation (lo), shared/compensated_sum.h.
// accumSum: RGB = sum of samples, w = number of finite samples; accumSq: RGB = sum of squares.
layout(set = 0, binding = 5, std430) buffer AccumSum { vec4 accumSum[]; };
layout(set = 0, binding = 6, std430) buffer AccumSq { vec4 accumSq[]; };
layout(set = 0, binding = 7, std430) buffer Counters { uint counters[]; };
layout(set = 0, binding = 8) uniform usamplerBuffer uEnvTexels;  // rgb radiance per map texel (bits)
layout(set = 0, binding = 9) uniform samplerBuffer uEnvDist;      // R32F: shared/distribution.h table
// Adaptive sampling (host/render/adaptive.h): [2i], [2i+1] = pixel i's decision-stream sums.
layout(set = 0, binding = 10, std430) buffer DecisionSums { vec4 decisionSums[]; };
layout(set = 0, binding = 11, std430) readonly buffer ActivePixels { uint activePixels[]; };
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

GpuPrim fetchPrim(uint i) {
    int base = int(i * GPU_PRIM_TEXELS);
    GpuPrim p;
    p.p0 = fetchF(uPrims, base);
    p.p1 = fetchF(uPrims, base + 1);
    p.p2 = fetchF(uPrims, base + 2);
    return p;
}

GpuMaterial fetchMaterial(uint i) {
    int base = int(i * GPU_MATERIAL_TEXELS);
    GpuMaterial m;
    m.m0 = fetchF(uMaterials, base);
    m.m1 = fetchF(uMaterials, base + 1);
    m.m2 = vec4(0.0f);
    m.m3 = vec4(0.0f);
    if (HAS_PBR) {  // only MAT_PBR reads them: other variants skip the two fetches
        m.m2 = fetchF(uMaterials, base + 2);
        m.m3 = fetchF(uMaterials, base + 3);
    }
    return m;
}

GpuLight fetchLight(uint i) {
    GpuLight l;
    l.l0 = fetchF(uLights, int(i));
    return l;
}

// ---- Instances (two-level BVH, shared/instance.h): compiled in only for scenes that have some.
// The traversal (lib/traverse_wide.glsl) tests VKP_HAS_INSTANCES.
layout(constant_id = 18) const bool HAS_INSTANCES = true;
#define VKP_HAS_INSTANCES HAS_INSTANCES
#include "shared/instance.h"
layout(set = 0, binding = 15) uniform usamplerBuffer uInstances;  // GPU_INSTANCE_TEXELS per instance

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
