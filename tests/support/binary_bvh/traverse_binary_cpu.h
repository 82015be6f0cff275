// CPU traversal of the binary BVH layout (FlatBvh::nodes): the twin of the layout benchmark's
// binary traversal, shaders/tests/traverse_binary.glsl, step for step (short stack, nearer inner
// child first, both leaf children's primitives tested in the node's step), same intersection code
// (shared/intersect.h), same pass counting. Test code: the product traverses the 4-wide layout only
// (its CPU twin is host/bvh/traverse_wide_cpu.h); this one is kept for the layout benchmark, the
// tests that compare the two layouts and the tests of the binary flattening.
#pragma once
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "bvh/flatten.h"
#include "bvh/trace_result.h"
#include "shared/gpu_types.h"
#include "shared/instance.h"

namespace vkp {

/// Entries of the traversal stack (VKP_TRAVERSE_STACK in shaders/tests/traverse_binary.glsl). A
/// tree of leaf depth <= 32 (the builder's bound) needs at most 31.
constexpr std::uint32_t kTraceStackSize = 32;

/// Closest hit with t in (tmin, tmax) of the ray o + t d (d unit length, world units) against the
/// nodes and prims of a FlatBvh; instances: FlatBvh::instances, which PRIM_INSTANCE primitives name
/// (a two-level BVH: such a leaf maps the ray into its object space and traverses its mesh's
/// bottom level from GpuInstance::info.y with a stack of its own, +1 pass for that loop's exit). A ray with a NaN component, or !(tmin < tmax), misses at no cost.
/// `passes` is the count the trace starts from (a path's previous traces), as in the GLSL.
/// Throws std::out_of_range if the nodes refer outside the arrays (a malformed BVH).
TraceResult traceClosestCpu(std::span<const gpu::GpuNode> nodes, std::span<const gpu::GpuPrim> prims,
                            std::span<const gpu::GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                            float tmin, float tmax, std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses);

/// Any hit with t in (tmin, tmax) (shadow rays): stops at the first primitive hit, which is
/// returned (not necessarily the closest).
TraceResult traceAnyCpu(std::span<const gpu::GpuNode> nodes, std::span<const gpu::GpuPrim> prims,
                        std::span<const gpu::GpuInstance> instances, const glm::vec3& o, const glm::vec3& d,
                        float tmin, float tmax, std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses);

/// The same without instances (a one-level BVH).
inline TraceResult traceClosestCpu(std::span<const gpu::GpuNode> nodes, std::span<const gpu::GpuPrim> prims,
                                   const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                                   std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses) {
    return traceClosestCpu(nodes, prims, {}, o, d, tmin, tmax, passes, maxPasses);
}
inline TraceResult traceAnyCpu(std::span<const gpu::GpuNode> nodes, std::span<const gpu::GpuPrim> prims,
                               const glm::vec3& o, const glm::vec3& d, float tmin, float tmax,
                               std::uint32_t passes = 0, std::uint32_t maxPasses = kTraceMaxPasses) {
    return traceAnyCpu(nodes, prims, {}, o, d, tmin, tmax, passes, maxPasses);
}

inline TraceResult traceClosestCpu(const FlatBvh& bvh, const glm::vec3& o, const glm::vec3& d,
                                   float tmin, float tmax) {
    return traceClosestCpu(bvh.nodes, bvh.prims, bvh.instances, o, d, tmin, tmax);
}
inline TraceResult traceAnyCpu(const FlatBvh& bvh, const glm::vec3& o, const glm::vec3& d,
                               float tmin, float tmax) {
    return traceAnyCpu(bvh.nodes, bvh.prims, bvh.instances, o, d, tmin, tmax);
}

}  // namespace vkp
