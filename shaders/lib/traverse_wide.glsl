// 4-wide BVH traversal (layout: shared/wide_bvh.h), the kernels' only one: include it through
// lib/traverse.glsl, which documents the interface (traceClosest, traceAny, traceClosestInstance),
// what the includer defines and the loop guard. The CPU twin is host/bvh/traverse_wide_cpu.cpp:
// keep the two in step (the GPU-vs-CPU tests compare hits and pass counts).
//
// The includer defines, BEFORE including this file (it declares no bindings):
//   GpuWideNode fetchWideNode(uint i);   // node i (8 texels)
//   GpuPrim fetchPrim(uint i);           // primitive i (3 texels)
// and may define VKP_HAS_SPHERES / VKP_HAS_QUADS / VKP_HAS_TRIANGLES as false, VKP_MAX_PASSES and
// VKP_ANY_HIT(primIndex, prim, ab, o, d) (false rejects a candidate hit).
//
// Algorithm: each step tests the node's four child boxes (intersectBox, component by component),
// tests the primitives of every hit leaf child in one inner loop, then sorts the hit inner
// children by entry distance (a 5-comparator network), descends into the nearest and pushes the
// others far to near, or pops. Stack: VKP_WIDE_STACK (96) entries, enough for the builder's trees
// (host/bvh/traverse_wide_cpu.h); an overflow drops the child and reports the trace cut short.
// Two levels (instances): a top-level leaf primitive of kind PRIM_INSTANCE starts the same loop
// (lib/traverse_wide_loop.glsl, a second function with its own stack) on its mesh's bottom level,
// in object space; the found hit carries across, since t is shared.
#ifndef VKP_TRAVERSE_WIDE_GLSL
#define VKP_TRAVERSE_WIDE_GLSL

#include "shared/intersect.h"
#include "shared/instance.h"
#include "shared/wide_bvh.h"
#include "lib/leaf_test.glsl"

// Instances (two-level BVH, shared/instance.h, host/bvh/two_level.h): compiled in when the includer
// defines VKP_HAS_INSTANCES as a true expression (a specialization constant in the renderer) and
// GpuInstance fetchInstance(uint i).
#ifndef VKP_HAS_INSTANCES
#define VKP_HAS_INSTANCES false
GpuInstance fetchInstance(uint i) {
    GpuInstance g;
    g.info = uvec4(0u);
    g.w2o0 = vec4(0.0); g.w2o1 = vec4(0.0); g.w2o2 = vec4(0.0);
    g.o2w0 = vec4(0.0); g.o2w1 = vec4(0.0); g.o2w2 = vec4(0.0);
    return g;
}
#endif

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

// The step's end: key/child sorted nearest first by the 5-comparator network, then the hit children
// after the first pushed far to near (the first is descended into).
#define VKP_WIDE_SORT_PUSH                      \
    VKP_SORT_PAIR(0, 1)                         \
    VKP_SORT_PAIR(2, 3)                         \
    VKP_SORT_PAIR(0, 2)                         \
    VKP_SORT_PAIR(1, 3)                         \
    VKP_SORT_PAIR(1, 2)                         \
    VKP_WIDE_PUSH(3)                            \
    VKP_WIDE_PUSH(2)                            \
    VKP_WIDE_PUSH(1)

// The bottom level of an instance (shared/instance.h): its triangles are plain leaf primitives.
#define VKP_WIDE_LOOP_FN vkpWideLoopBottom
#define VKP_WIDE_LEAF(p) vkpLeafHitInstance(p, o, d, tmin, t, primIndex, abHit, inst, instId)
#include "lib/traverse_wide_loop.glsl"
#undef VKP_WIDE_LOOP_FN
#undef VKP_WIDE_LEAF

#define VKP_TOP_LEAF_FN vkpWideTopLeaf
#define VKP_BOTTOM_LOOP_FN vkpWideLoopBottom
#define VKP_INSTANCE_ROOT(ins) ins.info.x
#include "lib/top_leaf.glsl"
#undef VKP_TOP_LEAF_FN
#undef VKP_BOTTOM_LOOP_FN
#undef VKP_INSTANCE_ROOT

#define VKP_WIDE_LOOP_FN vkpWideLoopTop
#define VKP_WIDE_LEAF(p) vkpWideTopLeaf(anyHit, p, o, d, tmin, t, primIndex, abHit, inst, passes)
#include "lib/traverse_wide_loop.glsl"
#undef VKP_WIDE_LOOP_FN
#undef VKP_WIDE_LEAF

bool vkpTraverseWide(const bool anyHit, vec3 o, vec3 d, float tmin, float tmax, out uint primIndex,
                     out float tHit, out vec2 abHit, out uint inst, inout uint passes) {
    primIndex = GPU_NODE_EMPTY;
    tHit = VKP_FAR;
    abHit = vec2(0.0);
    inst = GPU_NO_INSTANCE;
    bool nanRay = any(isnan(o)) || any(isnan(d));
    if (nanRay || !(tmin < tmax)) return false;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    bool found = vkpWideLoopTop(anyHit, 0u, o, d, tmin, t, primIndex, abHit, inst, GPU_NO_INSTANCE, passes);
    tHit = found ? t : VKP_FAR;
    if (!found) inst = GPU_NO_INSTANCE;
    return found;
}

#undef VKP_SORT_PAIR
#undef VKP_WIDE_PUSH
#undef VKP_WIDE_SORT_PUSH

/// Closest hit, as traceClosest; inst receives the instance whose triangle was hit (two-level BVH,
/// shared/instance.h; GPU_NO_INSTANCE: a top-level primitive, else primIndex and ab are the
/// object-space triangle and its surface parameters).
bool traceClosestInstance(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                          out vec2 ab, out uint inst, inout uint passes) {
    return vkpTraverseWide(false, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

/// Closest hit with t in (tmin, tmax) of the ray o + t d (d unit length, world units). Returns
/// true on a hit, with primIndex (into the primitive array), t and ab (intersectPrim's surface
/// parameters); on a miss primIndex = GPU_NODE_EMPTY, t = VKP_FAR. A ray with a NaN component or
/// !(tmin < tmax) misses without a pass. For `passes`, see the loop guard in lib/traverse.glsl.
bool traceClosest(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                  out vec2 ab, inout uint passes) {
    uint inst;
    return vkpTraverseWide(false, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

/// Shadow rays: true if anything is hit with t in (tmin, tmax); stops at the first hit.
bool traceAny(vec3 o, vec3 d, float tmin, float tmax, inout uint passes) {
    uint primIndex;
    float t;
    vec2 ab;
    uint inst;
    return vkpTraverseWide(true, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

#endif
