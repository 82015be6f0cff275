// The 4-wide GPU traversal (shaders/lib/traverse_wide.glsl, run through shaders/tests/bvh_trace.comp
// compiled with -DVKP_BVH_WIDE) against its CPU twin (host/bvh/traverse_wide_cpu) on the same
// nodes, prims and rays: the same closest hit (t bit-exact, primitive), any-hit answer and pass
// counts. The 100k-triangle mesh would expose a traversal cut short by lavapipe's loop limiter.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "bvh/flatten.h"
#include "bvh/traverse_wide_cpu.h"
#include "bvh/wide_pack.h"
#include "bvh_test_scenes.h"
#include "bvh_trace_wide.spv.h"
#include "gpu_env.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {
namespace {

struct Comparison {
    int mismatches = 0, passDifferences = 0, hits = 0, cutShort = 0;
};

Comparison compare(VulkanDevice& dev, const std::vector<Shape>& shapes, const std::vector<Ray>& rays) {
    const FlatBvh bvh = buildFlatBvh(makeScene(shapes));
    const std::vector<gpu::GpuWideNode> nodes = buildWideNodes(bvh);
    std::vector<glm::vec4> rayData;
    for (const Ray& r : rays) {
        rayData.emplace_back(r.o, r.tmin);
        rayData.emplace_back(r.d, r.tmax);
    }
    const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
    const auto texel = vk::BufferUsageFlagBits::eUniformTexelBuffer;
    GpuBuffer rayBuf(dev, rayData.size() * sizeof(glm::vec4), storage);
    rayBuf.upload(rayData.data(), rayData.size() * sizeof(glm::vec4));
    GpuBuffer nodeBuf(dev, nodes.size() * sizeof(gpu::GpuWideNode), texel);
    nodeBuf.upload(nodes.data(), nodes.size() * sizeof(gpu::GpuWideNode));
    GpuBuffer primBuf(dev, bvh.prims.size() * sizeof(gpu::GpuPrim), texel);
    primBuf.upload(bvh.prims.data(), bvh.prims.size() * sizeof(gpu::GpuPrim));
    GpuBuffer outBuf(dev, rays.size() * sizeof(glm::uvec4), storage);

    ComputePipelineDesc desc;
    desc.spirv = std::span<const std::uint32_t>(kBvhTraceWideSpv, std::size(kBvhTraceWideSpv));
    desc.bindings = {vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eUniformTexelBuffer,
                     vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eStorageBuffer};
    ComputePipeline pipe(dev, desc);
    const auto nodeView = nodeBuf.texelView();
    const auto primView = primBuf.texelView();
    pipe.bindBuffer(0, rayBuf.buffer());
    pipe.bindTexelView(1, *nodeView);
    pipe.bindTexelView(2, *primView);
    pipe.bindBuffer(3, outBuf.buffer());
    const auto groups = std::uint32_t((rays.size() + 63) / 64);
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) { pipe.recordDispatch(cmd, groups, 1, nullptr, 0); });
    std::vector<glm::uvec4> out(rays.size());
    outBuf.download(out.data(), out.size() * sizeof(glm::uvec4));
    dev.instance().throwIfValidationMessages("in the wide BVH traversal test");

    Comparison c;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        const TraceResult closest = traceClosestWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
        const TraceResult any = traceAnyWideCpu(nodes, bvh.prims, r.o, r.d, r.tmin, r.tmax);
        float gpuT;
        std::memcpy(&gpuT, &out[i].x, sizeof gpuT);
        const bool gpuAny = out[i].w & 1u;
        c.hits += closest.hit;
        c.cutShort += closest.cutShort() || any.cutShort();
        const bool same = std::memcmp(&gpuT, &closest.t, sizeof gpuT) == 0 && out[i].y == closest.prim && gpuAny == any.hit;
        if (!same && c.mismatches++ < 5)
            ADD_FAILURE() << "ray " << i << ": gpu t " << gpuT << " prim " << out[i].y << " any " << gpuAny << " | cpu t "
                          << closest.t << " prim " << closest.prim << " any " << any.hit;
        if (out[i].z != closest.passes || (out[i].w >> 1) != any.passes) ++c.passDifferences;
    }
    return c;
}

TEST(GpuBvhWide, MixedPrimitivesMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Shape> mix = randomTriangles(2000, 7);
    for (const Shape& s : randomSpheres(1000, 8)) mix.push_back(s);
    for (const Shape& s : randomQuads(1000, 9)) mix.push_back(s);
    const Comparison c = compare(dev, mix, randomRays(mix, 20000, 10));
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_EQ(c.passDifferences, 0);
    EXPECT_GT(c.hits, 5000);
}

TEST(GpuBvhWide, DenseMeshOf100kTrianglesMatchesCpu) {
    VKP_REQUIRE_DEVICE(dev);
    const std::vector<Shape> mesh = sphereMesh(224, 224, 5.0f);
    const Comparison c = compare(dev, mesh, randomRays(mesh, 5000, 11, 6.0f));
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_EQ(c.passDifferences, 0);
    EXPECT_EQ(c.cutShort, 0);
    EXPECT_GT(c.hits, 1000);
}

TEST(GpuBvhWide, AxisParallelAndNonFiniteRaysMatchCpu) {
    VKP_REQUIRE_DEVICE(dev);
    const std::vector<Shape> grid = axisQuadGrid();
    const std::vector<Ray> rays = axisAndNonFiniteRays();
    const Comparison c = compare(dev, grid, rays);
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_EQ(c.passDifferences, 0);
    EXPECT_GT(c.hits, 100);
}

TEST(GpuBvhWide, EmptyAndSinglePrimitiveScenes) {
    VKP_REQUIRE_DEVICE(dev);
    Comparison c = compare(dev, {}, randomRays({}, 100, 3));
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_EQ(c.hits, 0);
    const std::vector<Shape> one = {sphere(glm::vec3(0), 1.0f)};
    c = compare(dev, one, randomRays(one, 300, 3, 2.0f));
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_GT(c.hits, 0);
}

}  // namespace
}  // namespace vkp::test
