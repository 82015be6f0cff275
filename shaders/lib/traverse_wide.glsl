// 4-wide BVH traversal (layout: shared/wide_bvh.h). The CPU twin is host/bvh/traverse_wide_cpu.cpp:
// keep the two in step (the GPU-vs-CPU test compares hits and pass counts).
//
// The includer defines, BEFORE including this file (it declares no bindings):
//   GpuWideNode fetchWideNode(uint i);   // node i (8 texels)
//   GpuPrim fetchPrim(uint i);           // primitive i (3 texels)
// and may define VKP_HAS_SPHERES / VKP_HAS_PARALLELOGRAMS as false, VKP_MAX_PASSES and
// VKP_ANY_HIT(primIndex, prim, ab, o, d) (false rejects a candidate hit), as for
// lib/traverse.glsl, whose interface (traceClosest, traceAny) and loop guard this file repeats:
// include one of the two.
//
// Algorithm: each step tests the node's four child boxes (intersectBox, component by component),
// tests the primitives of every hit leaf child in one inner loop, then sorts the hit inner
// children by entry distance (a 5-comparator network), descends into the nearest and pushes the
// others far to near, or pops. Stack: VKP_WIDE_STACK (96) entries, enough for the builder's trees
// (host/bvh/traverse_wide_cpu.h); an overflow drops the child and reports the trace cut short.
#ifndef VKP_TRAVERSE_WIDE_GLSL
#define VKP_TRAVERSE_WIDE_GLSL

#include "shared/intersect.h"
#include "shared/wide_bvh.h"
#include "lib/leaf_test.glsl"

#ifndef VKP_MAX_PASSES
#define VKP_MAX_PASSES 60000u
#endif
#define VKP_WIDE_STACK 96u

// Compare-and-swap of the sorting network (swaps only on key[j] < key[i]), on vec4/uvec4 components.
#define VKP_SORT_PAIR(i, j)                     \
    if (key[j] < key[i]) {                      \
        float tk = key[i]; key[i] = key[j]; key[j] = tk; \
        uint tc = child[i]; child[i] = child[j]; child[j] = tc; \
    }

#define VKP_WIDE_PUSH(k)                        \
    if (key[k] < VKP_FAR) {                     \
        if (sp < VKP_WIDE_STACK) {              \
            stack[sp] = child[k];               \
            sp += 1u;                           \
        } else {                                \
            overflow = true;                    \
        }                                       \
    }

bool vkpTraverseWide(const bool anyHit, vec3 o, vec3 d, float tmin, float tmax, out uint primIndex,
                     out float tHit, out vec2 abHit, inout uint passes) {
    primIndex = GPU_NODE_EMPTY;
    tHit = VKP_FAR;
    abHit = vec2(0.0);
    bool nanRay = any(isnan(o)) || any(isnan(d));
    if (nanRay || !(tmin < tmax)) return false;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    vec3 invD = safeInverse(d);
    uint stack[VKP_WIDE_STACK];
    uint sp = 0u;
    uint node = 0u;
    bool finished = false;
    bool overflow = false;
    bool found = false;
    while (passes < uint(VKP_MAX_PASSES)) {
        passes += 2u;
        GpuWideNode n = fetchWideNode(node);
        vec4 tb;
        tb.x = intersectBox(vec3(n.loX.x, n.loY.x, n.loZ.x), vec3(n.hiX.x, n.hiY.x, n.hiZ.x), o, invD, tmin, t);
        tb.y = intersectBox(vec3(n.loX.y, n.loY.y, n.loZ.y), vec3(n.hiX.y, n.hiY.y, n.hiZ.y), o, invD, tmin, t);
        tb.z = intersectBox(vec3(n.loX.z, n.loY.z, n.loZ.z), vec3(n.hiX.z, n.hiY.z, n.hiZ.z), o, invD, tmin, t);
        tb.w = intersectBox(vec3(n.loX.w, n.loY.w, n.loZ.w), vec3(n.hiX.w, n.hiY.w, n.hiZ.w), o, invD, tmin, t);
        bvec4 hit = lessThan(tb, vec4(VKP_FAR));
        uvec4 nLeaf = mix(uvec4(0u), n.count, hit);
        uint s1 = nLeaf.x;
        uint s2 = s1 + nLeaf.y;
        uint s3 = s2 + nLeaf.z;
        uint total = s3 + nLeaf.w;
        for (uint i = 0u; i < total; ++i) {
            passes += 1u;
            uint p = (i < s1) ? n.index.x + i
                   : (i < s2) ? n.index.y + (i - s1)
                   : (i < s3) ? n.index.z + (i - s2)
                              : n.index.w + (i - s3);
            if (vkpLeafHit(p, o, d, tmin, t, primIndex, abHit)) {
                found = true;
                if (anyHit) break;
            }
        }
        if (anyHit && found) {
            finished = true;
            break;
        }
        bvec4 inner = bvec4(uvec4(hit) * uvec4(equal(n.count, uvec4(0u))));
#ifdef VKP_WIDE_RECULL
        // Bench variant: also drop inner children entered beyond the hit the leaves just found (the
        // box test repeated with tmax = t: enter <= t * VKP_BOX_EXIT_SCALE, intersect.h).
        inner = bvec4(uvec4(inner) * uvec4(lessThanEqual(tb, vec4(t * VKP_BOX_EXIT_SCALE))));
#endif
#ifdef VKP_WIDE_UNORDERED
        // Bench variant: visit hit inner children in slot order (the keys are slot numbers), to
        // measure what the nearest-first order buys; same sorting work.
        vec4 key = mix(vec4(VKP_FAR), vec4(0.0, 1.0, 2.0, 3.0), inner);
#else
        vec4 key = mix(vec4(VKP_FAR), tb, inner);
#endif
        uvec4 child = n.index;
        VKP_SORT_PAIR(0, 1)
        VKP_SORT_PAIR(2, 3)
        VKP_SORT_PAIR(0, 2)
        VKP_SORT_PAIR(1, 3)
        VKP_SORT_PAIR(1, 2)
        VKP_WIDE_PUSH(3)
        VKP_WIDE_PUSH(2)
        VKP_WIDE_PUSH(1)
        if (key[0] < VKP_FAR) {
            node = child[0];
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

#undef VKP_SORT_PAIR
#undef VKP_WIDE_PUSH

/// Closest hit, as lib/traverse.glsl's traceClosest, through the 4-wide BVH.
bool traceClosest(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                  out vec2 ab, inout uint passes) {
    return vkpTraverseWide(false, o, d, tmin, tmax, primIndex, t, ab, passes);
}

/// Shadow rays: true if anything is hit with t in (tmin, tmax); stops at the first hit.
bool traceAny(vec3 o, vec3 d, float tmin, float tmax, inout uint passes) {
    uint primIndex;
    float t;
    vec2 ab;
    return vkpTraverseWide(true, o, d, tmin, tmax, primIndex, t, ab, passes);
}

#endif
