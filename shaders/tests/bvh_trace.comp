// Test and bench kernel: traces a list of rays through the BVH, so a GPU test can compare a device
// traversal with its CPU twin, and the layout micro-benchmark (tests/bench/bench_bvh_layout.cpp)
// can time the layouts. With -DVKP_BVH_WIDE it runs the kernels' traversal (lib/traverse.glsl, the
// 4-wide layout; CPU twin host/bvh/traverse_wide_cpu.h); without, the binary layout that only the
// benchmark and the layout-comparing tests keep (tests/traverse_binary.glsl; CPU twin
// tests/bench/traverse_binary_cpu.h).
//   binding 0 (SSBO, read):  per ray two vec4: (origin.xyz, tmin), (direction.xyz, tmax);
//                            the ray count is the bound range / 32 bytes; invocation
//                            x + y * (groups in x * 64) traces ray number that (extra ones idle)
//   binding 1 (usamplerBuffer RGBA32UI): BVH nodes (binary: FlatBvh::nodes, 4 texels each)
//   binding 2 (usamplerBuffer RGBA32UI): primitives (FlatBvh::prims, 3 texels each)
//   With -DVKP_FETCH_SSBO (a bench variant, tests/bench/bench_bvh_layout.cpp) bindings 1 and 2
//   are read-only storage buffers of uvec4 holding the same data. With -DVKP_FETCH_BDA the same
//   data is read through buffer device addresses (GL_EXT_buffer_reference) given as push
//   constants: uvec2 node address, uvec2 primitive address. With -DVKP_BVH_WIDE binding 1
//   holds 4-wide nodes (shared/wide_bvh.h, 8 texels each) traversed by lib/traverse.glsl; with
//   -DVKP_BVH_WIDE -DVKP_BVH_WIDE8 8-wide nodes (two 4-wide halves, 16 texels each) traversed by
//   tests/traverse_wide8.glsl (the benchmark's).
//   binding 3 (SSBO, written): per ray a uvec4:
//       x: bits of the closest hit t (VKP_FAR on a miss), y: primitive index (0xffffffff on a
//       miss), z: passes of traceClosest (starting from 0), w: traceAny's result (bit 0) |
//       its passes << 1 (starting from 0)
//   With -DVKP_INSTANCES (either layout; two-level BVH, shared/instance.h): binding 4 (usamplerBuffer
//   RGBA32UI) holds the GpuInstances, and binding 5 (SSBO, written) per ray the instance of the
//   closest hit (GPU_NO_INSTANCE for a top-level primitive or a miss).
#version 460
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "shared/gpu_types.h"

layout(std430, binding = 0) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = 3) writeonly buffer Results { uvec4 results[]; };

#if defined(VKP_FETCH_BDA)
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Uvec4Data { uvec4 texel[]; };
layout(push_constant) uniform DataAddresses { uvec2 nodes; uvec2 prims; } addresses;
#define VKP_NODE_TEXEL(b) Uvec4Data(addresses.nodes).texel[b]
#define VKP_PRIM_TEXEL(b) Uvec4Data(addresses.prims).texel[b]
#elif defined(VKP_FETCH_SSBO)
layout(std430, binding = 1) readonly buffer NodeData { uvec4 nodeData[]; };
layout(std430, binding = 2) readonly buffer PrimData { uvec4 primData[]; };
#define VKP_NODE_TEXEL(b) nodeData[b]
#define VKP_PRIM_TEXEL(b) primData[b]
#else
layout(binding = 1) uniform usamplerBuffer nodeTexels;
layout(binding = 2) uniform usamplerBuffer primTexels;
#define VKP_NODE_TEXEL(b) texelFetch(nodeTexels, b)
#define VKP_PRIM_TEXEL(b) texelFetch(primTexels, b)
#endif

#if defined(VKP_BVH_WIDE) && defined(VKP_BVH_WIDE_QUANTIZED)
#include "tests/wide_quantized.h"
// Bench variant: quantized 4-wide nodes (4 texels), decoded into the GpuWideNode that the
// traversal reads.
GpuWideNode fetchWideNode(uint i) {
    int b = int(i * QUANTIZED_NODE_TEXELS);
    return decodeQuantizedWideNode(VKP_NODE_TEXEL(b), VKP_NODE_TEXEL(b + 1), VKP_NODE_TEXEL(b + 2), VKP_NODE_TEXEL(b + 3));
}
#elif defined(VKP_BVH_WIDE)
#include "shared/wide_bvh.h"
GpuWideNode fetchWideNode(uint i) {
    int b = int(i * GPU_WIDE_NODE_TEXELS);
    GpuWideNode n;
    n.loX = uintBitsToFloat(VKP_NODE_TEXEL(b));
    n.hiX = uintBitsToFloat(VKP_NODE_TEXEL(b + 1));
    n.loY = uintBitsToFloat(VKP_NODE_TEXEL(b + 2));
    n.hiY = uintBitsToFloat(VKP_NODE_TEXEL(b + 3));
    n.loZ = uintBitsToFloat(VKP_NODE_TEXEL(b + 4));
    n.hiZ = uintBitsToFloat(VKP_NODE_TEXEL(b + 5));
    n.index = VKP_NODE_TEXEL(b + 6);
    n.count = VKP_NODE_TEXEL(b + 7);
    return n;
}
#else
GpuNode fetchNode(uint i) {
    int b = int(i * GPU_NODE_TEXELS);
    GpuNode n;
    n.a = uintBitsToFloat(VKP_NODE_TEXEL(b));
    n.b = uintBitsToFloat(VKP_NODE_TEXEL(b + 1));
    n.c = uintBitsToFloat(VKP_NODE_TEXEL(b + 2));
    n.d = uintBitsToFloat(VKP_NODE_TEXEL(b + 3));
    return n;
}
#endif

GpuPrim fetchPrim(uint i) {
    int b = int(i * GPU_PRIM_TEXELS);
    GpuPrim p;
    p.p0 = uintBitsToFloat(VKP_PRIM_TEXEL(b));
    p.p1 = uintBitsToFloat(VKP_PRIM_TEXEL(b + 1));
    p.p2 = uintBitsToFloat(VKP_PRIM_TEXEL(b + 2));
    return p;
}

#ifdef VKP_INSTANCES
#include "shared/instance.h"
layout(binding = 4) uniform usamplerBuffer instanceTexels;
layout(std430, binding = 5) writeonly buffer InstanceResults { uint instanceResults[]; };
#define VKP_HAS_INSTANCES true
GpuInstance fetchInstance(uint i) {
    int b = int(i * GPU_INSTANCE_TEXELS);
    GpuInstance g;
    g.info = texelFetch(instanceTexels, b);
    g.w2o0 = uintBitsToFloat(texelFetch(instanceTexels, b + 1));
    g.w2o1 = uintBitsToFloat(texelFetch(instanceTexels, b + 2));
    g.w2o2 = uintBitsToFloat(texelFetch(instanceTexels, b + 3));
    g.o2w0 = uintBitsToFloat(texelFetch(instanceTexels, b + 4));
    g.o2w1 = uintBitsToFloat(texelFetch(instanceTexels, b + 5));
    g.o2w2 = uintBitsToFloat(texelFetch(instanceTexels, b + 6));
    return g;
}
#endif

#if defined(VKP_BVH_WIDE8)
#include "tests/traverse_wide8.glsl"  // the benchmark's 8-wide nodes (two 4-wide halves each)
#elif defined(VKP_BVH_WIDE)
#include "lib/traverse.glsl"  // the kernels' traversal (4-wide)
#else
#include "tests/traverse_binary.glsl"  // the benchmark's binary layout
#endif

void main() {
    // Works with any dispatch shape that has at least `count` invocations (rows of workgroups).
    uint id = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    uint count = uint(rays.length()) / 2u;
    if (id >= count) return;
    vec4 od = rays[2u * id];
    vec4 dd = rays[2u * id + 1u];
    uint prim;
    float t;
    vec2 ab;
    uint passesClosest = 0u;
#ifdef VKP_INSTANCES
    uint inst;
    traceClosestInstance(od.xyz, dd.xyz, od.w, dd.w, prim, t, ab, inst, passesClosest);
    instanceResults[id] = inst;
#else
    traceClosest(od.xyz, dd.xyz, od.w, dd.w, prim, t, ab, passesClosest);
#endif
    uint passesAny = 0u;
    bool anyHit = traceAny(od.xyz, dd.xyz, od.w, dd.w, passesAny);
    results[id] = uvec4(floatBitsToUint(t), prim, passesClosest, (anyHit ? 1u : 0u) | (passesAny << 1u));
}
