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
// current hit. Instances (two-level BVH): a top-level PRIM_INSTANCE leaf runs the same loop
// (lib/traverse_binary_loop.glsl, a second function with its own stack) on its mesh's bottom level
// from GpuInstance::info.y, in object space, as lib/traverse_wide.glsl does from info.x.
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

#include "shared/instance.h"
// Instances (two-level BVH): as in lib/traverse_wide.glsl, compiled in when the includer defines
// VKP_HAS_INSTANCES as a true expression and GpuInstance fetchInstance(uint i).
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

// The bottom level of an instance: its triangles are plain leaf primitives.
#define VKP_BIN_LOOP_FN vkpBinaryLoopBottom
#define VKP_BIN_LEAF(p) vkpLeafHitInstance(p, o, d, tmin, t, primIndex, abHit, inst, instId)
#include "lib/traverse_binary_loop.glsl"
#undef VKP_BIN_LOOP_FN
#undef VKP_BIN_LEAF

#define VKP_TOP_LEAF_FN vkpBinaryTopLeaf
#define VKP_BOTTOM_LOOP_FN vkpBinaryLoopBottom
#define VKP_INSTANCE_ROOT(ins) ins.info.y
#include "lib/top_leaf.glsl"
#undef VKP_TOP_LEAF_FN
#undef VKP_BOTTOM_LOOP_FN
#undef VKP_INSTANCE_ROOT

#define VKP_BIN_LOOP_FN vkpBinaryLoopTop
#define VKP_BIN_LEAF(p) vkpBinaryTopLeaf(anyHit, p, o, d, tmin, t, primIndex, abHit, inst, passes)
#include "lib/traverse_binary_loop.glsl"
#undef VKP_BIN_LOOP_FN
#undef VKP_BIN_LEAF

// Shared body of traceClosest (anyHit = false) and traceAny (anyHit = true); the constant
// argument is folded after inlining.
bool vkpTraverse(const bool anyHit, vec3 o, vec3 d, float tmin, float tmax, out uint primIndex,
                 out float tHit, out vec2 abHit, out uint inst, inout uint passes) {
    primIndex = GPU_NODE_EMPTY;
    tHit = VKP_FAR;
    abHit = vec2(0.0);
    inst = GPU_NO_INSTANCE;
    bool nanRay = any(isnan(o)) || any(isnan(d));
    if (nanRay || !(tmin < tmax)) return false;
    float t = (tmax < VKP_FAR) ? tmax : VKP_FAR;
    bool found = vkpBinaryLoopTop(anyHit, 0u, o, d, tmin, t, primIndex, abHit, inst, GPU_NO_INSTANCE, passes);
    tHit = found ? t : VKP_FAR;
    if (!found) inst = GPU_NO_INSTANCE;
    return found;
}

/// Closest hit with t in (tmin, tmax) of the ray o + t d (d unit length, world units). Returns
/// true on a hit, with primIndex (into the primitive array), t and ab (intersectPrim's surface
/// parameters); on a miss primIndex = GPU_NODE_EMPTY, t = VKP_FAR. A ray with a NaN component or
/// !(tmin < tmax) misses without a pass. See the loop guard above for `passes`.
bool traceClosest(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                  out vec2 ab, inout uint passes) {
    uint inst;
    return vkpTraverse(false, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

/// Shadow rays: true if anything is hit with t in (tmin, tmax); stops at the first hit.
bool traceAny(vec3 o, vec3 d, float tmin, float tmax, inout uint passes) {
    uint primIndex;
    float t;
    vec2 ab;
    uint inst;
    return vkpTraverse(true, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

/// Closest hit, as traceClosest; inst receives the instance whose triangle was hit (two-level BVH,
/// shared/instance.h; GPU_NO_INSTANCE: a top-level primitive, else primIndex and ab are the
/// object-space triangle and its surface parameters).
bool traceClosestInstance(vec3 o, vec3 d, float tmin, float tmax, out uint primIndex, out float t,
                          out vec2 ab, out uint inst, inout uint passes) {
    return vkpTraverse(false, o, d, tmin, tmax, primIndex, t, ab, inst, passes);
}

#endif  // VKP_BVH_WIDE
#endif
