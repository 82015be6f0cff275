// The test of one leaf primitive, shared by the 4-wide traversal (lib/traverse_wide.glsl, the
// kernels') and the binary one of the layout benchmark (shaders/tests/traverse_binary.glsl); its
// CPU twin: host/bvh/traverse_shared_cpu.h. The includer
// defines fetchPrim(uint) and, optionally,
// VKP_ANY_HIT(primIndex, prim, ab, o, d) (false rejects a candidate hit: alpha, lib/alpha.glsl).
#ifndef VKP_LEAF_TEST_GLSL
#define VKP_LEAF_TEST_GLSL
#include "shared/intersect.h"

/// Primitive p against the ray o + t d, t in (tmin, t): when it is hit before t (and the any-hit
/// hook accepts the hit), t, primIndex and abHit become its hit and the result is true.
bool vkpLeafHit(uint p, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex, inout vec2 abHit) {
    vec2 ab;
    GpuPrim pr = fetchPrim(p);
    float th = intersectPrim(pr, o, d, tmin, t, ab);
#ifdef VKP_ANY_HIT
    if (th < t && !VKP_ANY_HIT(p, pr, ab, o, d)) th = VKP_FAR;  // a hole or passed through
#endif
    if (!(th < t)) return false;
    t = th;
    primIndex = p;
    abHit = ab;
    return true;
}

/// vkpLeafHit that also records which instance the hit belongs to (instId: GPU_NO_INSTANCE at the
/// top level of a two-level BVH, shared/instance.h).
bool vkpLeafHitInstance(uint p, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex, inout vec2 abHit,
                        inout uint inst, uint instId) {
    if (!vkpLeafHit(p, o, d, tmin, t, primIndex, abHit)) return false;
    inst = instId;
    return true;
}

#endif
