// A GPU traversal kernel (shaders/tests/bvh_trace.comp, binary or 4-wide) against its CPU twin on
// the same nodes, primitives and rays, and the scenarios both layouts are tested on
// (tests/gpu/test_gpu_bvh.cpp, test_gpu_bvh_wide.cpp): the same closest hit (t bit-exact,
// primitive), the same any-hit answer and the same loop-pass counts, on a device that rounds as the
// host (device_rounding.h: lavapipe). On a device that rounds otherwise (a GPU's division and sqrt
// are within a few ulps, and it may fuse a * b + c), the same primitive at t within kRayTRelative
// of the ray's scale,
// the same any-hit answer, and a few rays more that rounding turned (a ray grazing an edge, two
// boxes entered at the same distance): BvhComparison::allowed().
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <span>
#include <vector>

#include "bvh/flatten.h"
#include "bvh/trace_result.h"
#include "shared/instance.h"
#include "bvh_test_scenes.h"
#include "device_rounding.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"
#include "vk/device.h"

namespace vkp::test {

/// A closest hit's t agrees up to rounding within this fraction of t plus the ray origin's largest
/// coordinate (an origin rounded in its last bits moves t by that much in absolute terms).
inline constexpr float kRayTRelative = 1e-5f;

struct BvhComparison {
    /// Rays whose results disagree: bitMismatches on a device that rounds as the host, else
    /// roundingMismatches. Expected at most allowed(), as are the rays with other pass counts.
    int mismatches = 0, passDifferences = 0, hits = 0, cutShort = 0;
    int instanceHits = 0;  ///< closest hits on an instance's triangle (two-level BVH)
    int bitMismatches = 0;       ///< t, primitive, instance or any-hit answer differ in any bit
    int roundingMismatches = 0;  ///< ... beyond rounding: another primitive or instance, t beyond kRayTRelative, any-hit
    bool exact = true;           ///< the device rounds as the host (device_rounding.h)
    int roundingAllowance = 0;   ///< max(1, rays / 1000): what a device that rounds otherwise may have
    /// Rays that may disagree (in results, and in pass counts): 0 where the device rounds as the host.
    int allowed() const { return exact ? 0 : roundingAllowance; }
};

/// Hit distances of `ray` that agree up to rounding: within kRayTRelative of (|t| + the origin's
/// largest coordinate), or equal (both misses, VKP_FAR).
inline bool sameDistanceUpToRounding(float gpuT, float cpuT, const Ray& ray) {
    const float scale = std::abs(cpuT) + std::max({std::abs(ray.o.x), std::abs(ray.o.y), std::abs(ray.o.z)});
    return gpuT == cpuT || std::abs(gpuT - cpuT) <= kRayTRelative * scale;
}

/// The closest hits (gpuT, gpuPrim) and `cpu` of `ray` agree up to rounding: the same primitive (or
/// both miss) and sameDistanceUpToRounding.
inline bool sameHitUpToRounding(float gpuT, std::uint32_t gpuPrim, const TraceResult& cpu, const Ray& ray) {
    return gpuPrim == cpu.prim && sameDistanceUpToRounding(gpuT, cpu.t, ray);
}

/// The CPU twin of one layout: closest hit (any = false) or any hit (any = true) of a ray.
using CpuTrace = std::function<TraceResult(const Ray&, bool any)>;

/// Runs the traversal kernel `spirv` (shaders/tests/bvh_trace.comp or a variant; bindings: rays,
/// nodes, prims, results) on `nodeBytes` and `prims` for every ray; returns its uvec4 per ray
/// (t bits, primitive, closest-hit passes, any-hit bit | any-hit passes << 1). Rows of 1024
/// workgroups of 64 rays: the kernel maps invocation (x, y) to ray x + y * (groups in x) * 64.
/// With instances (the kernel variant bvh_trace_wide_instances), binding 4 holds them and binding 5
/// receives each ray's closest-hit instance, returned in *instanceOut.
inline std::vector<glm::uvec4> runTraversalKernel(VulkanDevice& dev, std::span<const std::uint32_t> spirv,
                                                  const void* nodeBytes, std::size_t nodeSize,
                                                  const std::vector<gpu::GpuPrim>& prims, const std::vector<Ray>& rays,
                                                  const char* what, std::span<const gpu::GpuInstance> instances = {},
                                                  std::vector<std::uint32_t>* instanceOut = nullptr) {
    std::vector<glm::vec4> rayData;
    for (const Ray& r : rays) {
        rayData.emplace_back(r.o, r.tmin);
        rayData.emplace_back(r.d, r.tmax);
    }
    const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
    const auto texel = vk::BufferUsageFlagBits::eUniformTexelBuffer;
    GpuBuffer rayBuf(dev, rayData.size() * sizeof(glm::vec4), storage);
    rayBuf.upload(rayData.data(), rayData.size() * sizeof(glm::vec4));
    GpuBuffer nodeBuf(dev, nodeSize, texel);
    nodeBuf.upload(nodeBytes, nodeSize);
    GpuBuffer primBuf(dev, prims.size() * sizeof(gpu::GpuPrim), texel);
    primBuf.upload(prims.data(), prims.size() * sizeof(gpu::GpuPrim));
    GpuBuffer outBuf(dev, rays.size() * sizeof(glm::uvec4), storage);
    const bool withInstances = !instances.empty();
    GpuBuffer instBuf(dev, std::max<std::size_t>(instances.size(), 1) * sizeof(gpu::GpuInstance), texel);
    if (withInstances) instBuf.upload(instances.data(), instances.size() * sizeof(gpu::GpuInstance));
    GpuBuffer instOutBuf(dev, std::max<std::size_t>(rays.size(), 1) * sizeof(std::uint32_t), storage);
    ComputePipelineDesc desc;
    desc.spirv = spirv;
    desc.bindings = {vk::DescriptorType::eStorageBuffer, vk::DescriptorType::eUniformTexelBuffer,
                     vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eStorageBuffer};
    if (withInstances) {
        desc.bindings.push_back(vk::DescriptorType::eUniformTexelBuffer);
        desc.bindings.push_back(vk::DescriptorType::eStorageBuffer);
    }
    ComputePipeline pipe(dev, desc);
    const auto nodeView = nodeBuf.texelView();
    const auto primView = primBuf.texelView();
    const auto instView = instBuf.texelView();
    pipe.bindBuffer(0, rayBuf.buffer());
    pipe.bindTexelView(1, *nodeView);
    pipe.bindTexelView(2, *primView);
    pipe.bindBuffer(3, outBuf.buffer());
    if (withInstances) {
        pipe.bindTexelView(4, *instView);
        pipe.bindBuffer(5, instOutBuf.buffer());
    }
    const auto groups = std::uint32_t((rays.size() + 63) / 64);
    const std::uint32_t gx = std::max(1u, std::min(groups, 1024u)), gy = (groups + gx - 1) / gx;
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) { pipe.recordDispatch(cmd, gx, gy, nullptr, 0); });
    std::vector<glm::uvec4> out(rays.size());
    outBuf.download(out.data(), out.size() * sizeof(glm::uvec4));
    if (withInstances && instanceOut) {
        instanceOut->resize(rays.size());
        instOutBuf.download(instanceOut->data(), rays.size() * sizeof(std::uint32_t));
    }
    dev.instance().throwIfValidationMessages(std::string("in the ") + what + " traversal test");
    return out;
}

/// runTraversalKernel, then every ray's result compared with `cpu`.
/// With instances, the closest hit's instance must agree too.
inline BvhComparison compareTraversal(VulkanDevice& dev, std::span<const std::uint32_t> spirv, const void* nodeBytes,
                                      std::size_t nodeSize, const std::vector<gpu::GpuPrim>& prims,
                                      const std::vector<Ray>& rays, const CpuTrace& cpu, const char* what,
                                      std::span<const gpu::GpuInstance> instances = {}) {
    std::vector<std::uint32_t> gpuInstance;
    const std::vector<glm::uvec4> out =
        runTraversalKernel(dev, spirv, nodeBytes, nodeSize, prims, rays, what, instances, &gpuInstance);
    BvhComparison c;
    const bool exact = roundsLikeTheHost(dev);
    c.exact = exact;
    c.roundingAllowance = std::max(1, int(rays.size()) / 1000);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const TraceResult closest = cpu(rays[i], false);
        const TraceResult any = cpu(rays[i], true);
        float gpuT;
        std::memcpy(&gpuT, &out[i].x, sizeof gpuT);
        const bool gpuAny = out[i].w & 1u;
        c.hits += closest.hit;
        c.cutShort += closest.cutShort() || any.cutShort();
        const std::uint32_t gpuInst = instances.empty() ? gpu::GPU_NO_INSTANCE : gpuInstance[i];
        c.instanceHits += closest.hit && closest.instance != gpu::GPU_NO_INSTANCE;
        const bool answers = gpuAny == any.hit && gpuInst == closest.instance;
        const bool bits = answers && std::memcmp(&gpuT, &closest.t, sizeof gpuT) == 0 && out[i].y == closest.prim;
        const bool rounding = answers && sameHitUpToRounding(gpuT, out[i].y, closest, rays[i]);
        c.bitMismatches += !bits;
        c.roundingMismatches += !rounding;
        if (!(exact ? bits : rounding) && c.mismatches++ < 5)
            std::printf("  %s ray %zu: gpu t %.9g prim %u instance %u any %d | cpu t %.9g prim %u instance %u any %d\n",
                        what, i, double(gpuT), out[i].y, gpuInst, int(gpuAny), double(closest.t), closest.prim,
                        closest.instance, int(any.hit));
        if (out[i].z != closest.passes || (out[i].w >> 1) != any.passes) ++c.passDifferences;
    }
    if (!exact)
        std::printf("  %s on a device that %s: %d rays differ in bits, %d beyond rounding (%d allowed), %d in passes (%d allowed)\n",
                    what, probeRounding(dev).describe().c_str(), c.bitMismatches, c.roundingMismatches,
                    c.allowed(), c.passDifferences, c.allowed());
    return c;
}

/// Builds the layout's BVH for `shapes`, runs the kernel and the CPU twin on `rays`.
using BvhCompare = std::function<BvhComparison(const std::vector<Shape>& shapes, const std::vector<Ray>& rays)>;

/// 2000 triangles, 1000 spheres and 1000 quads, 20,000 random rays.
inline void expectMixedPrimitivesMatch(const BvhCompare& compare) {
    std::vector<Shape> mix = randomTriangles(2000, 7);
    for (const Shape& s : randomSpheres(1000, 8)) mix.push_back(s);
    for (const Shape& s : randomQuads(1000, 9)) mix.push_back(s);
    const BvhComparison c = compare(mix, randomRays(mix, 20000, 10));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_GT(c.hits, 5000);  // the rays do hit things: the comparison is not vacuous
}

/// A 100k-triangle sphere mesh: a traversal cut short by lavapipe's loop limiter would show here.
inline void expectDenseMeshMatches(const BvhCompare& compare) {
    const std::vector<Shape> mesh = sphereMesh(224, 224, 5.0f);
    ASSERT_GE(mesh.size(), 100000u);
    const BvhComparison c = compare(mesh, randomRays(mesh, 5000, 11, 6.0f));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_EQ(c.cutShort, 0);
    EXPECT_GT(c.hits, 1000);
}

/// Axis-parallel rays in the planes of axis-aligned quads, and non-finite rays.
inline void expectAxisAndNonFiniteRaysMatch(const BvhCompare& compare) {
    const BvhComparison c = compare(axisQuadGrid(), axisAndNonFiniteRays());
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_LE(c.passDifferences, c.allowed());
    EXPECT_GT(c.hits, 100);
}

/// No primitive at all, and a single sphere.
inline void expectEmptyAndSinglePrimitiveScenesMatch(const BvhCompare& compare) {
    BvhComparison c = compare({}, randomRays({}, 100, 3));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_EQ(c.hits, 0);
    const std::vector<Shape> one = {sphere(glm::vec3(0), 1.0f)};
    c = compare(one, randomRays(one, 300, 3, 2.0f));
    EXPECT_LE(c.mismatches, c.allowed());
    EXPECT_GT(c.hits, 0);
}

}  // namespace vkp::test
