// The 4-wide GPU traversal (shaders/lib/traverse_wide.glsl, run through shaders/tests/bvh_trace.comp
// compiled with -DVKP_BVH_WIDE) against its CPU twin (host/bvh/traverse_wide_cpu) on the same
// nodes, prims and rays: the same closest hit (t bit-exact, primitive), any-hit answer and pass
// counts (up to rounding on a device that rounds otherwise: bvh_trace_compare.h). The 100k-triangle
// mesh would expose a traversal cut short by lavapipe's loop limiter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

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

/// The rounding-tolerant comparison (on a device that rounds otherwise than the host,
/// bvh_trace_compare.h), measured on this device: the GPU against the CPU twin tracing each ray
/// nudged by two ulps in every component of its origin and direction (what another rounding of the
/// ray's set-up does) differs in bits but stays within the allowance, while the same twin with
/// directions turned by 1e-4 rad (a defect ten times larger than rounding) fails it many times over.
TEST(GpuBvhWide, RoundingTolerantComparisonSeparatesRoundingFromOtherHits) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Shape> mix = randomTriangles(2000, 7);
    for (const Shape& s : randomSpheres(1000, 8)) mix.push_back(s);
    for (const Shape& s : randomQuads(1000, 9)) mix.push_back(s);
    const std::vector<Ray> rays = randomRays(mix, 20000, 10);
    const FlatBvh bvh = buildFlatBvh(makeScene(mix));
    const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
    auto compareWith = [&](const std::function<Ray(Ray)>& change, const char* what) {
        return compareTraversal(
            dev, std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv)), nodes.data(),
            nodes.size() * sizeof(gpu::GpuWideNode), bvh.prims, rays,
            [&](const Ray& ray, bool any) {
                const Ray r = change(ray);
                return any ? traceAnyWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax)
                           : traceClosestWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
            },
            what);
    };
    auto ulps = [](float x, int k) {
        for (int i = 0; i < k; ++i) x = std::nextafter(x, INFINITY);
        return x;
    };
    const BvhComparison nudged = compareWith(
        [&](Ray r) {
            for (int a = 0; a < 3; ++a) {
                r.o[a] = ulps(r.o[a], 2);
                r.d[a] = ulps(r.d[a], 2);
            }
            return r;
        },
        "rays nudged by 2 ulps");
    const BvhComparison turned = compareWith(
        [](Ray r) {
            const glm::vec3 side = glm::normalize(glm::cross(r.d, std::abs(r.d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
            r.d = glm::normalize(r.d + 1e-4f * side);
            return r;
        },
        "rays turned by 1e-4 rad");
    std::printf("nudged: %d of 20000 rays differ in bits, %d beyond rounding (allowance %d), %d in passes (allowance %d); "
                "turned: %d beyond rounding\n",
                nudged.bitMismatches, nudged.roundingMismatches, nudged.roundingAllowance, nudged.passDifferences,
                nudged.roundingAllowance, turned.roundingMismatches);
    EXPECT_GT(nudged.hits, 5000);
    EXPECT_GT(nudged.bitMismatches, 1000) << "the nudge must reach the hits' bits, or this measures nothing";
    EXPECT_LE(nudged.roundingMismatches, nudged.roundingAllowance);
    EXPECT_LE(nudged.passDifferences, nudged.roundingAllowance);
    EXPECT_GT(turned.roundingMismatches, 20 * turned.roundingAllowance);
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
