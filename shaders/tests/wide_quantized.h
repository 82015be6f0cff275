// Quantized 4-wide nodes, a lever measured by the layout micro-benchmark (issue 18; compressed wide
// BVH nodes, Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", HPG 2017, sec. 3.1): the same tree as GpuWideNode (shared/wide_bvh.h) in 4
// texels (64 bytes) instead of 8. Per node: the union box's min corner `origin` (floats) and a
// power-of-two step per axis; per child and axis an 8-bit lower and upper grid coordinate, so that
// lo = origin + qlo * step, hi = origin + qhi * step (one rounding: q * step is exact) contain the
// child's box. Declared once for the bench kernel (shaders/tests/bvh_trace.comp,
// VKP_BVH_WIDE_QUANTIZED), which decodes a node into a GpuWideNode and traverses it unchanged,
// and for the packer (tests/bench/wide_quantized_pack.h), which checks its boxes with this decode.
//   texel 0: origin.xyz (float bits); w: the steps' biased exponents (byte a = axis a, step 2^(e - 127))
//   texel 1: qlo per axis (x, y, z; byte k = child k); w: counts (byte k = child k's count)
//   texel 2: qhi per axis; w: 0
//   texel 3: index (child k's node or first primitive, as GpuWideNode::index)
// Empty slots: qlo 255, qhi 0 on every axis (inverted by 255 steps; every step is at least 2^-8 of
// the origin's magnitude and at least 2^-100, so an empty slot is never entered).
#ifndef VKP_WIDE_QUANTIZED_H
#define VKP_WIDE_QUANTIZED_H
#include "shared/glsl_compat.h"
#include "shared/wide_bvh.h"

VKP_BEGIN

const uint QUANTIZED_NODE_TEXELS = 4u;

/// The step 2^(e - 127) of a biased exponent e in [1, 254].
VKP_FN float quantizedStep(uint biasedExponent) { return uintBitsToFloat(biasedExponent << 23u); }

/// Grid coordinate q (0..255) of an axis whose grid starts at origin (world units).
VKP_FN float quantizedCoordinate(float origin, uint q, float step) { return origin + float(q) * step; }

/// The four children's coordinates on one axis: byte k of `bytes` is child k's q.
VKP_FN vec4 quantizedCoordinates(float origin, uint bytes, float step) {
    return vec4(quantizedCoordinate(origin, bytes & 0xffu, step), quantizedCoordinate(origin, (bytes >> 8u) & 0xffu, step),
                quantizedCoordinate(origin, (bytes >> 16u) & 0xffu, step), quantizedCoordinate(origin, bytes >> 24u, step));
}

/// The node whose four texels are t0..t3, with boxes that contain the packed children's.
VKP_FN GpuWideNode decodeQuantizedWideNode(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3) {
    vec3 origin = vec3(uintBitsToFloat(t0.x), uintBitsToFloat(t0.y), uintBitsToFloat(t0.z));
    vec3 step = vec3(quantizedStep(t0.w & 0xffu), quantizedStep((t0.w >> 8u) & 0xffu), quantizedStep((t0.w >> 16u) & 0xffu));
    GpuWideNode n;
    n.loX = quantizedCoordinates(origin.x, t1.x, step.x);
    n.loY = quantizedCoordinates(origin.y, t1.y, step.y);
    n.loZ = quantizedCoordinates(origin.z, t1.z, step.z);
    n.hiX = quantizedCoordinates(origin.x, t2.x, step.x);
    n.hiY = quantizedCoordinates(origin.y, t2.y, step.y);
    n.hiZ = quantizedCoordinates(origin.z, t2.z, step.z);
    n.count = uvec4(t1.w & 0xffu, (t1.w >> 8u) & 0xffu, (t1.w >> 16u) & 0xffu, t1.w >> 24u);
    n.index = t3;
    return n;
}

VKP_END
#endif
