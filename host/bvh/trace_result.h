// The result of a CPU trace of the flattened BVH, shared by the CPU twin of the kernel's 4-wide
// traversal (bvh/traverse_wide_cpu.h) and the test-side twin of the benchmark's binary traversal
// (tests/support/binary_bvh/traverse_binary_cpu.h).
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "shared/gpu_types.h"
#include "shared/instance.h"

namespace vkp {

/// Default pass budget of one trace call (VKP_MAX_PASSES in shaders/lib/traverse.glsl).
constexpr std::uint32_t kTraceMaxPasses = 60000;
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

}  // namespace vkp
