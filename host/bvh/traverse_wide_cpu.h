// CPU traversal of the 4-wide BVH layout (shared/wide_bvh.h): the host twin of
// shaders/lib/traverse_wide.glsl, step for step (four box tests per node, the primitives of every
// hit leaf child tested in the node's step, hit inner children visited nearest first through a
// 4-element sorting network, the others pushed far to near), same pass counting as the binary
// traversal (tests/support/binary_bvh: +2 per node step, +1 per primitive). Used as the reference in tests.
// Instances (two-level BVH, host/bvh/two_level.h): a PRIM_INSTANCE leaf primitive maps the ray into
// its object space (shared/instance.h) and traverses its mesh's bottom level from its root, with a
// stack of its own; that costs +1 pass (the bottom-level loop's exit) on top of its steps.
#pragma once
#include <span>

#include "bvh/trace_result.h"
#include "shared/instance.h"
#include "shared/wide_bvh.h"

namespace vkp {

/// Stack entries of the wide traversal (VKP_WIDE_STACK in traverse_wide.glsl): at most 3 pushes
/// per wide level, and a collapsed tree of a binary tree of leaf depth <= 32 has at most 31 levels
/// of wide nodes, so 96 entries never overflow for the builder's trees. Each BVH level has its own.
constexpr std::uint32_t kWideTraceStackSize = 96;

/// Closest hit, as traceClosestCpu, through wide nodes (prims: the FlatBvh's prims; instances:
/// FlatBvh::instances, which PRIM_INSTANCE primitives name). TraceResult::instance tells which
/// instance's triangle was hit (GPU_NO_INSTANCE: a top-level primitive).
TraceResult traceClosestWideCpu(std::span<const gpu::GpuWideNode> nodes, std::span<const gpu::GpuPrim> prims,
                                std::span<const gpu::GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                                float tmin, float tmax, std::uint32_t passes = 0,
                                std::uint32_t maxPasses = kTraceMaxPasses);

/// Any hit, as traceAnyCpu, through wide nodes.
TraceResult traceAnyWideCpu(std::span<const gpu::GpuWideNode> nodes, std::span<const gpu::GpuPrim> prims,
                            std::span<const gpu::GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                            float tmin, float tmax, std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses);

/// The same without instances (a one-level BVH).
inline TraceResult traceClosestWideCpu(std::span<const gpu::GpuWideNode> nodes, std::span<const gpu::GpuPrim> prims,
                                       const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                                       std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses) {
    return traceClosestWideCpu(nodes, prims, {}, o, d, tmin, tmax, passes, maxPasses);
}
inline TraceResult traceAnyWideCpu(std::span<const gpu::GpuWideNode> nodes, std::span<const gpu::GpuPrim> prims,
                                   const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                                   std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses) {
    return traceAnyWideCpu(nodes, prims, {}, o, d, tmin, tmax, passes, maxPasses);
}

}  // namespace vkp
