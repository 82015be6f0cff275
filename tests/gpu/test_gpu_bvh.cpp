// The GPU traversal (shaders/lib/traverse.glsl, run through shaders/tests/bvh_trace.comp) against
// its CPU twin (tests/support/binary_bvh/traverse_binary_cpu) on the same flattened BVH and the same rays: the same
// closest hit (t bit-exact, primitive), the same any-hit answer and the same loop-pass counts (on a
// device that rounds otherwise than the host: up to rounding, bvh_trace_compare.h).
// The 100k-triangle mesh would expose a traversal cut short by lavapipe's loop limiter.
#include <gtest/gtest.h>

#include "bvh_trace.spv.h"
#include "bvh_trace_compare.h"
#include "gpu_env.h"
#include "traverse_binary_cpu.h"

namespace vkp::test {
namespace {

/// The binary layout: FlatBvh nodes, traverse_binary_cpu.h.
BvhCompare comparer(VulkanDevice& dev) {
    return [&dev](const std::vector<Shape>& shapes, const std::vector<Ray>& rays) {
        const FlatBvh bvh = buildFlatBvh(makeScene(shapes));
        return compareTraversal(
            dev, std::span<const std::uint32_t>(kBvhTraceSpv, std::size(kBvhTraceSpv)), bvh.nodes.data(),
            bvh.nodes.size() * sizeof(gpu::GpuNode), bvh.prims, rays,
            [&](const Ray& r, bool any) {
                return any ? traceAnyCpu(bvh, r.o, r.d, r.tmin, r.tmax) : traceClosestCpu(bvh, r.o, r.d, r.tmin, r.tmax);
            },
            "binary BVH");
    };
}

TEST(GpuBvh, MixedPrimitivesMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectMixedPrimitivesMatch(comparer(dev));
}

TEST(GpuBvh, DenseMeshOf100kTrianglesMatchesCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectDenseMeshMatches(comparer(dev));
}

TEST(GpuBvh, AxisParallelAndNonFiniteRaysMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectAxisAndNonFiniteRaysMatch(comparer(dev));
}

TEST(GpuBvh, EmptyAndSinglePrimitiveScenes) {
    VKP_REQUIRE_DEVICE(dev);
    expectEmptyAndSinglePrimitiveScenesMatch(comparer(dev));
}

}  // namespace
}  // namespace vkp::test
