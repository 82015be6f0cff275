// The 4-wide GPU traversal (shaders/lib/traverse_wide.glsl, run through shaders/tests/bvh_trace.comp
// compiled with -DVKP_BVH_WIDE) against its CPU twin (host/bvh/traverse_wide_cpu) on the same
// nodes, prims and rays: the same closest hit (t bit-exact, primitive), any-hit answer and pass
// counts. The 100k-triangle mesh would expose a traversal cut short by lavapipe's loop limiter.
#include <gtest/gtest.h>

#include "bvh/traverse_wide_cpu.h"
#include "bvh/wide_pack.h"
#include "bvh_trace_compare.h"
#include "bvh_trace_wide.spv.h"
#include "gpu_env.h"

namespace vkp::test {
namespace {

/// The 4-wide layout: buildWideNodes, traverse_wide_cpu.h; `options`: how the tree is built.
BvhCompare comparer(VulkanDevice& dev, const BvhBuildOptions& options = {}) {
    return [&dev, options](const std::vector<Shape>& shapes, const std::vector<Ray>& rays) {
        const FlatBvh bvh = buildFlatBvh(makeScene(shapes), options);
        const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
        return compareTraversal(
            dev, std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)), nodes.data(),
            nodes.size() * sizeof(gpu::GpuWideNode), bvh.prims, rays,
            [&](const Ray& r, bool any) {
                return any ? traceAnyWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax)
                           : traceClosestWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
            },
            "4-wide BVH");
    };
}

TEST(GpuBvhWide, MixedPrimitivesMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectMixedPrimitivesMatch(comparer(dev));
}

TEST(GpuBvhWide, DenseMeshOf100kTrianglesMatchesCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectDenseMeshMatches(comparer(dev));
}

TEST(GpuBvhWide, AxisParallelAndNonFiniteRaysMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectAxisAndNonFiniteRaysMatch(comparer(dev));
}

TEST(GpuBvhWide, EmptyAndSinglePrimitiveScenes) {
    VKP_REQUIRE_DEVICE(dev);
    expectEmptyAndSinglePrimitiveScenesMatch(comparer(dev));
}

/// Spatial splits (host/bvh/sbvh.h): a primitive may be in several leaves. The unit tests check
/// the CPU traversal of such trees against brute force; here the kernel against the CPU.
BvhBuildOptions withSpatialSplits() {  // the whole budget: more cut references to check
    BvhBuildOptions o;
    o.spatialSplits = 1.0f;
    return o;
}

TEST(GpuBvhWide, SpatialSplitsMixedPrimitivesMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectMixedPrimitivesMatch(comparer(dev, withSpatialSplits()));
}

TEST(GpuBvhWide, SpatialSplitsAxisParallelAndNonFiniteRaysMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    expectAxisAndNonFiniteRaysMatch(comparer(dev, withSpatialSplits()));
}

}  // namespace
}  // namespace vkp::test
