// CPU traversal of a flattened BVH (the GPU layout): the host twin of shaders/lib/traverse.glsl,
// same algorithm step for step (short stack, nearer inner child first, both leaf children's
// primitives tested in the node's step), same intersection code (shared/intersect.h), same pass
// counting. Used as the reference in tests and for host-side ray queries.
#pragma once
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "bvh/flatten.h"
#include "shared/gpu_types.h"
#include "shared/instance.h"

namespace vkp {

/// Default pass budget of one trace call (VKP_MAX_PASSES in traverse.glsl).
constexpr std::uint32_t kTraceMaxPasses = 60000;
/// Entries of the traversal stack (VKP_TRAVERSE_STACK in traverse.glsl). A tree of leaf depth
/// <= 32 (the builder's bound) needs at most 31.
constexpr std::uint32_t kTraceStackSize = 32;

/// Result of a trace. Passes count like the GLSL: +2 per node step (the step and the leaf loop's
/// exit), +1 per primitive tested. When the budget is used up or the stack would overflow, the
/// traversal stops and passes is raised to >= maxPasses: the caller treats the path as cut short
/// (cutShort()); hit/t/prim then describe what was found so far.
struct TraceResult {
    bool hit = false;
    float t = gpu::VKP_FAR;                 ///< hit distance (world units), VKP_FAR on a miss
    std::uint32_t prim = gpu::GPU_NODE_EMPTY;  ///< index into FlatBvh::prims
    glm::vec2 ab{0.0f};                     ///< surface parameters (see intersectPrim; object space for an instance's triangle)
    std::uint32_t instance = gpu::GPU_NO_INSTANCE;  ///< FlatBvh::instances index of the hit's instance
    std::uint32_t passes = 0;               ///< passes counted so far (the caller's start value +)
    std::uint32_t maxPasses = kTraceMaxPasses;
    bool cutShort() const { return passes >= maxPasses; }
};

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
