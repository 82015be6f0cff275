// Instances through the device's traversals (shaders/lib/traverse_wide.glsl and the binary
// lib/traverse.glsl with VKP_HAS_INSTANCES, run by shaders/tests/bvh_trace.comp compiled with
// -DVKP_INSTANCES) against their CPU twins (host/bvh/traverse_wide_cpu, tests/support/binary_bvh/traverse_binary_cpu) on the same
// two-level BVH and rays: the same closest hit (t bit-exact, primitive, instance), any-hit answer
// and pass counts (up to rounding on a device that rounds otherwise: bvh_trace_compare.h). The
// scene's instances translate, rotate, scale non-uniformly and mirror two shared meshes
// (tests/support/instance_test_scenes.h).
#include <gtest/gtest.h>

#include "bvh/traverse_wide_cpu.h"
#include "bvh/two_level.h"
#include "bvh_trace_compare.h"
#include "bvh_trace_instances.spv.h"
#include "bvh_trace_wide_instances.spv.h"
#include "gpu_env.h"
#include "traverse_binary_cpu.h"
#include "instance_test_scenes.h"

namespace vkp::test {
namespace {

/// The binary layout: FlatBvh::nodes, traverse_binary_cpu.h.
BvhComparison compareInstancedBinary(VulkanDevice& dev, const Scene& scene, const std::vector<Ray>& rays) {
    const FlatBvh bvh = buildTwoLevelBvh(scene);
    return compareTraversal(
        dev, std::span<const std::uint32_t>(kBvhTraceInstancesSpv, std::size(kBvhTraceInstancesSpv)), bvh.nodes.data(),
        bvh.nodes.size() * sizeof(gpu::GpuNode), bvh.prims, rays,
        [&](const Ray& r, bool any) {
            return any ? traceAnyCpu(bvh.nodes, bvh.prims, bvh.instances, r.o, r.d, r.tmin, r.tmax)
                       : traceClosestCpu(bvh.nodes, bvh.prims, bvh.instances, r.o, r.d, r.tmin, r.tmax);
        },
        "two-level binary BVH", bvh.instances);
}

BvhComparison compareInstanced(VulkanDevice& dev, const Scene& scene, const std::vector<Ray>& rays) {
    const FlatBvh bvh = buildTwoLevelBvh(scene);
    return compareTraversal(
        dev, std::span<const std::uint32_t>(kBvhTraceWideInstancesSpv, std::size(kBvhTraceWideInstancesSpv)),
        bvh.wideNodes.data(), bvh.wideNodes.size() * sizeof(gpu::GpuWideNode), bvh.prims, rays,
        [&](const Ray& r, bool any) {
            return any ? traceAnyWideCpu(bvh.wideNodes, bvh.prims, bvh.instances, r.o, r.d, r.tmin, r.tmax)
                       : traceClosestWideCpu(bvh.wideNodes, bvh.prims, bvh.instances, r.o, r.d, r.tmin, r.tmax);
        },
        "two-level 4-wide BVH", bvh.instances);
}

TEST(GpuBvhInstances, HitsMatchCpuOnTheSameRays) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene scene = instancedScene();
    const BvhComparison c = compareInstanced(dev, scene, randomRays(flattenedScene(scene).shapes, 20000, 71, 25.0f));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_EQ(c.cutShort, 0);
    EXPECT_GT(c.instanceHits, 4000);  // the rays do reach the instances
}

TEST(GpuBvhInstances, AxisParallelAndNonFiniteRaysMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    // The axis grid as a shared mesh used by a mirrored and a scaled instance, next to its own copy.
    Scene scene = makeScene(axisQuadGrid());
    InstancedMesh grid;
    grid.name = "grid";
    for (const Shape& q : axisQuadGrid()) {  // quads as two triangles
        grid.shapes.push_back(triangle(q.p0, q.p0 + q.p1, q.p0 + q.p1 + q.p2));
        grid.shapes.push_back(triangle(q.p0, q.p0 + q.p1 + q.p2, q.p0 + q.p2));
    }
    scene.meshes.push_back(grid);
    scene.instances.push_back({0, glm::dmat4(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(-1, 0, 0, 1))});
    scene.instances.push_back({0, glm::dmat4(glm::dvec4(2, 0, 0, 0), glm::dvec4(0, 0.5, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, 0, 5, 1))});
    const BvhComparison c = compareInstanced(dev, scene, axisAndNonFiniteRays());
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_GT(c.hits, 100);
    EXPECT_GT(c.instanceHits, 10);
}

TEST(GpuBvhInstances, BinaryLayoutHitsMatchCpuOnTheSameRays) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene scene = instancedScene();
    const BvhComparison c = compareInstancedBinary(dev, scene, randomRays(flattenedScene(scene).shapes, 20000, 72, 25.0f));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_EQ(c.cutShort, 0);
    EXPECT_GT(c.instanceHits, 4000);
}

}  // namespace
}  // namespace vkp::test
