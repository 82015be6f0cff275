// 4-wide BVH node layout (8 texels, 128 bytes): the boxes of four children stored per axis
// (structure of arrays), so that one node step tests four boxes with vec4 arithmetic. Built by
// collapsing the binary SAH tree (host/bvh/wide_collapse.h), packed by host/bvh/wide_pack.h,
// traversed by shaders/lib/traverse_wide.glsl and its CPU twin host/bvh/traverse_wide_cpu.h.
// The primitives are FlatBvh::prims unchanged (leaves are the binary tree's leaves).
#ifndef VKP_WIDE_BVH_H
#define VKP_WIDE_BVH_H
#include "glsl_compat.h"

VKP_BEGIN

// Child k (k = 0..3, the vec4 component) of a node:
//   lo.k = (loX.k, loY.k, loZ.k), hi.k = (hiX.k, hiY.k, hiZ.k): its box;
//   count.k == 0: an inner child, index.k = its node index (or GPU_NODE_EMPTY for an empty slot,
//                 whose box is inverted, min = +big, max = -big, so it is never entered);
//   count.k >= 1: a leaf of prims [index.k, index.k + count.k).
// Node 0 is the root. A scene with no primitive has one node of four empty slots.
struct GpuWideNode {
    vec4 loX;
    vec4 hiX;
    vec4 loY;
    vec4 hiY;
    vec4 loZ;
    vec4 hiZ;
    uvec4 index;
    uvec4 count;
};
const uint GPU_WIDE_NODE_TEXELS = 8u;
const uint GPU_WIDE_ARITY = 4u;

VKP_END
#endif
