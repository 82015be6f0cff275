// BVH traversal for the kernels. The CPU twin is host/bvh/traverse_cpu.cpp: keep the two in step
// (the GPU-vs-CPU test compares hits and pass counts).
//
// The includer defines, BEFORE including this file (it declares no bindings):
//   GpuNode fetchNode(uint i);   // node i of the flattened BVH (host/bvh/flatten.h, 4 texels)
//   GpuPrim fetchPrim(uint i);   // primitive i (3 texels)
// and may define VKP_HAS_SPHERES / VKP_HAS_PARALLELOGRAMS as false (shared/intersect.h),
// VKP_MAX_PASSES, and VKP_ANY_HIT(primIndex, prim, ab, o, d): false rejects a candidate hit (alpha
// cut-outs and stochastic transparency, lib/alpha.glsl).
//
// Algorithm: binary nodes holding both children's boxes; each step tests the two boxes, tests the
// primitives of every hit leaf child at once (one inner loop), then descends into the nearer hit
// inner child and pushes the other onto a short stack, or pops. Closest hit culls boxes beyond the
// current hit.
//
// Loop guard: lavapipe silently ends loops after 65,535 passes per invocation (DESIGN.md).
// `passes` counts like lavapipe: +2 per step (the step and the exit of its leaf loop), +1 per
// primitive tested. The loop stops when passes >= VKP_MAX_PASSES. If the traversal did not finish
// (budget used up, the driver ended the loop early, or the stack overflowed), passes is raised to
// at least VKP_MAX_PASSES on return: the caller must then treat the path as cut short (and count it
// in COUNTER_LOOP_GUARD). The count is per lane; lavapipe counts the maximum over 8 lanes, which is
// why a loop ended by the driver is detected separately (the loop leaves without finishing).
//
// Stack: VKP_TRAVERSE_STACK (32) entries. The builder bounds the leaf depth by 32, so at most 31
// are used. On overflow (only with a foreign, deeper tree) the far child is dropped and the trace
// is reported as cut short as above.
#ifndef VKP_TRAVERSE_GLSL
#define VKP_TRAVERSE_GLSL

// Node layout. The path-tracing kernels (lib/bindings.glsl, node texels in uNodes) traverse the
// 4-wide layout (shared/wide_bvh.h, lib/traverse_wide.glsl; the host uploads FlatBvh::wideNodes),
// which measured faster on lavapipe (README "Performance", "Device data layout"). Any includer may
// choose it by defining VKP_BVH_WIDE and fetchWideNode, or keep this binary traversal by defining
// VKP_BVH_BINARY (or by not including lib/bindings.glsl).
#if defined(VKP_BINDINGS_GLSL) && !defined(VKP_BVH_BINARY) && !defined(VKP_BVH_WIDE)
#define VKP_BVH_WIDE 1
#include "shared/wide_bvh.h"
GpuWideNode fetchWideNode(uint i) {
    int b = int(i * GPU_WIDE_NODE_TEXELS);
    GpuWideNode n;
    n.loX = uintBitsToFloat(texelFetch(uNodes, b));
    n.hiX = uintBitsToFloat(texelFetch(uNodes, b + 1));
    n.loY = uintBitsToFloat(texelFetch(uNodes, b + 2));
    n.hiY = uintBitsToFloat(texelFetch(uNodes, b + 3));
    n.loZ = uintBitsToFloat(texelFetch(uNodes, b + 4));
    n.hiZ = uintBitsToFloat(texelFetch(uNodes, b + 5));
    n.index = texelFetch(uNodes, b + 6);
    n.count = texelFetch(uNodes, b + 7);
    return n;
}
#endif

#ifdef VKP_BVH_WIDE
#include "lib/traverse_wide.glsl"
#else

#include "shared/intersect.h"
#include "lib/leaf_test.glsl"

#ifndef VKP_MAX_PASSES
#define VKP_MAX_PASSES 60000u
#endif
#define VKP_TRAVERSE_STACK 32u

// Shared body of traceClosest (anyHit = false) and traceAny (anyHit = true); the constant
// argument is folded after inlining.
bool vkpTraverse(const bool anyHit, vec3 o, vec3 d, float tmin, float tmax, out uint primIndex,
                 out float tHit, out vec2 abHit, inout uint passes) {
    primIndex = GPU_NODE_EMPTY;
    tHit = VKP_FAR;
    abHit = vec2(0.0);
    bool nanRay = any(isnan(o)) || any(isnan(d));
    if (nanRay || !(tmin < tmax)) return false;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    vec3 invD = safeInverse(d);
    uint stack[VKP_TRAVERSE_STACK];
    uint sp = 0u;
    uint node = 0u;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        passes += 2u;
        GpuNode n = fetchNode(node);
        float tl = intersectBox(n.a.xyz, n.b.xyz, o, invD, tmin, t);
        float tr = intersectBox(n.c.xyz, n.d.xyz, o, invD, tmin, t);
        uint il = floatBitsToUint(n.a.w);
        uint cl = floatBitsToUint(n.b.w);
        uint ir = floatBitsToUint(n.c.w);
        uint cr = floatBitsToUint(n.d.w);
        bool hitL = tl < VKP_FAR;
        bool hitR = tr < VKP_FAR;
        uint nl = hitL ? cl : 0u;
        uint nr = hitR ? cr : 0u;
        for (uint i = 0u; i < nl + nr; ++i) {
            passes += 1u;
            uint p = (i < nl) ? il + i : ir + (i - nl);
            if (vkpLeafHit(p, o, d, tmin, t, primIndex, abHit)) {
                found = true;
                if (anyHit) break;
            }
        }
        if (anyHit && found) {
            finished = true;
            break;
        }
        bool innerL = hitL && cl == 0u;
        bool innerR = hitR && cr == 0u;
        if (innerL && innerR) {
            bool leftFirst = tl <= tr;
            if (sp < VKP_TRAVERSE_STACK) {
                stack[sp] = leftFirst ? ir : il;
                sp += 1u;
            } else {
                overflow = true;
            }
            node = leftFirst ? il : ir;
        } else if (innerL || innerR) {
            node = innerL ? il : ir;
        } else if (sp > 0u) {
            sp -= 1u;
            node = stack[sp];
        } else {
            finished = true;
            break;
        }
    }
    if (!finished || overflow) passes = max(passes, uint(VKP_MAX_PASSES));
    tHit = found ? t : VKP_FAR;
    return found;
}

/// Closest hit with t in (tmin, tmax) of the ray o + t d (d unit length, world units). Returns
/// true on a hit, with primIndex (into the primitive array), t and ab (intersectPrim's surface
/// parameters); on a miss primIndex = GPU_NODE_EMPTY, t = VKP_FAR. A ray with a NaN component or
/// !(tmin < tmax) misses without a pass. See the loop guard above for `passes`.
bool traceClosest(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                  out vec2 ab, inout uint passes) {
    return vkpTraverse(false, o, d, tmin, tmax, primIndex, t, ab, passes);
}

/// Shadow rays: true if anything is hit with t in (tmin, tmax); stops at the first hit.
bool traceAny(vec3 o, vec3 d, float tmin, float tmax, inout uint passes) {
    uint primIndex;
    float t;
    vec2 ab;
    return vkpTraverse(true, o, d, tmin, tmax, primIndex, t, ab, passes);
}

/// The binary layout does not traverse instances (two-level BVH, shared/instance.h): the renderer
/// always uses the 4-wide layout, and this traversal is kept for comparison. A PRIM_INSTANCE
/// primitive has NaN coordinates and is never hit here; its CPU twin (host/bvh/traverse_cpu.cpp)
/// throws on one. This wrapper only keeps the interface of lib/traverse_wide.glsl.
bool traceClosestInstance(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                          out vec2 ab, out uint inst, inout uint passes) {
    inst = 0xffffffffu;  // GPU_NO_INSTANCE
    return vkpTraverse(false, o, d, tmin, tmax, primIndex, t, ab, passes);
}

#endif  // VKP_BVH_WIDE
#endif
