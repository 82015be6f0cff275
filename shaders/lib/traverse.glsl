// BVH traversal for the kernels: the 4-wide layout (shared/wide_bvh.h; the host uploads
// FlatBvh::wideNodes), the only layout the path tracer has. It measured faster on lavapipe than
// the binary layout (docs/performance.md, "Device data layout"); the algorithm is in
// lib/traverse_wide.glsl, its CPU twin host/bvh/traverse_wide_cpu.cpp (the GPU-vs-CPU tests compare
// hits and pass counts). The binary traversal survives only on the test side, for the layout
// micro-benchmark and the tests that compare layouts (shaders/tests/traverse_binary.glsl, included
// by shaders/tests/bvh_trace.comp without -DVKP_BVH_WIDE; CPU twin tests/bench/traverse_binary_cpu.h).
//
// Interface:
//   traceClosest(o, d, tmin, tmax, out primIndex, out t, out ab, inout passes)
//   traceAny(o, d, tmin, tmax, inout passes)                          (shadow rays)
//   traceClosestInstance(o, d, tmin, tmax, out primIndex, out t, out ab, out inst, inout passes)
//
// The includer defines, BEFORE including this file:
//   GpuPrim fetchPrim(uint i);           // primitive i (3 texels)
//   GpuWideNode fetchWideNode(uint i);   // node i (8 texels); defined here from uNodes when
//                                        // lib/bindings.glsl was included (the path tracer)
// and may define VKP_HAS_SPHERES / VKP_HAS_QUADS / VKP_HAS_TRIANGLES as false (shared/intersect.h),
// VKP_MAX_PASSES, VKP_ANY_HIT(primIndex, prim, ab, o, d): false rejects a candidate hit (alpha
// cut-outs and stochastic transparency, lib/alpha.glsl), and VKP_HAS_INSTANCES with
// GpuInstance fetchInstance(uint i) (two-level BVH, lib/traverse_wide.glsl).
//
// Loop guard: lavapipe silently ends loops after 65,535 passes per invocation (docs/design.md, "The loop limiter").
// `passes` counts like lavapipe: +2 per step (the step and the exit of its leaf loop), +1 per
// primitive tested, +1 per instance entered (its bottom-level loop's exit). The loop stops when
// passes >= VKP_MAX_PASSES. If the traversal did not finish (budget used up, the driver ended the
// loop early, or the stack overflowed), passes is raised to at least VKP_MAX_PASSES on return: the
// caller must then treat the path as cut short (and count it in COUNTER_LOOP_GUARD). The count is
// per lane; lavapipe counts the maximum over 8 lanes, which is why a loop ended by the driver is
// detected separately (the loop leaves without finishing).
#ifndef VKP_TRAVERSE_GLSL
#define VKP_TRAVERSE_GLSL

#ifdef VKP_BINDINGS_GLSL
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

#include "lib/traverse_wide.glsl"

#endif
