// Binary BVH traversal: NOT the product's. The path tracer traverses the 4-wide layout
// (lib/traverse.glsl -> lib/traverse_wide.glsl), which measured faster on lavapipe
// (docs/performance.md, "Device data layout"). This one is kept, on the test side, for the layout
// micro-benchmark (tests/bench/bench_bvh_layout.cpp) and the tests that compare layouts: the test
// kernel shaders/tests/bvh_trace.comp includes it when compiled without -DVKP_BVH_WIDE. Its CPU
// twin is tests/bench/traverse_binary_cpu.cpp: keep the two in step (tests/gpu/test_gpu_bvh.cpp
// compares hits and pass counts).
//
// The interface is lib/traverse.glsl's (traceClosest, traceAny, traceClosestInstance), and so are
// the includer's duties, except that it defines, BEFORE including this file:
//   GpuNode fetchNode(uint i);   // node i of the flattened BVH (FlatBvh::nodes, host/bvh/flatten.h, 4 texels)
//   GpuPrim fetchPrim(uint i);   // primitive i (3 texels)
// and may define VKP_HAS_SPHERES / VKP_HAS_QUADS / VKP_HAS_TRIANGLES as false (shared/intersect.h),
// VKP_MAX_PASSES, VKP_ANY_HIT(primIndex, prim, ab, o, d), and VKP_HAS_INSTANCES with
// GpuInstance fetchInstance(uint i). Loop guard and pass counting: as in lib/traverse.glsl.
//
// Algorithm: binary nodes holding both children's boxes; each step tests the two boxes, tests the
// primitives of every hit leaf child at once (one inner loop), then descends into the nearer hit
// inner child and pushes the other onto a short stack, or pops. Closest hit culls boxes beyond the
// current hit. Instances (two-level BVH): a top-level PRIM_INSTANCE leaf runs the same loop
// (tests/traverse_binary_loop.glsl, a second function with its own stack) on its mesh's bottom
// level from GpuInstance::info.y, in object space, as lib/traverse_wide.glsl does from info.x.
// Leaf tests and top-level leaves are shared with the 4-wide traversal (lib/leaf_test.glsl,
// lib/top_leaf.glsl).
//
// Stack: VKP_TRAVERSE_STACK (32) entries. The builder bounds the leaf depth by 32, so at most 31
// are used. On overflow (only with a foreign, deeper tree) the far child is dropped and the trace
// is reported as cut short (passes >= VKP_MAX_PASSES).
#ifndef VKP_TRAVERSE_BINARY_GLSL
#define VKP_TRAVERSE_BINARY_GLSL

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
#include "tests/traverse_binary_loop.glsl"
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
#include "tests/traverse_binary_loop.glsl"
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
/// !(tmin < tmax) misses without a pass. For `passes`, see the loop guard in lib/traverse.glsl.
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

#endif
