// The GLSL build of shared/distribution.h and shared/environment_map.h on the device (kernel
// shaders/tests/distribution_test.comp, the table in an R32F texel buffer read through distFetch
// as in the path tracer) against the C++ build on the same tables and inputs: edge values of u and
// 20000 uniform pairs. Then a chi-square of the DEVICE's samples against the host pdf.
// Tolerances: the two builds take the same branches of the binary search (comparisons of the same
// floats), so cells and densities are equal bit for bit; positions differ by the device's division
// (~0.7 ulp) and sin/cos/atan/acos (a few 1e-7); inverses by the same. Environment directions whose
// point lies within rounding of a texel edge may fall in the neighbouring texel in one build: those
// are counted as flips (a handful at most) and not compared.
// Significance: each chi-square runs at statsAlpha() (stat_suite.h, the stats suite's Sidak
// budget of kStatsChi2Budget tests, family-wise 1%); 2 tests here.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <span>
#include <vector>

#include "distribution_test.spv.h"
#include "gpu_env.h"
#include "render/distribution_table.h"
#include "render/environment.h"
#include "shared/environment_map.h"
#include "stat_suite.h"
#include "vk/buffer.h"
#include "vk/compute_pipeline.h"

namespace vkp::test {
namespace {

struct Push {
    std::uint32_t routine, count, nu, nv;
    float c, s;
};
struct Out {
    glm::vec4 o0, o1;
};

std::vector<Out> runKernel(VulkanDevice& dev, const std::vector<float>& table, const Push& pushIn,
                           const std::vector<glm::vec4>& items) {
    static std::unique_ptr<ComputePipeline> pipe;
    if (!pipe) {
        ComputePipelineDesc d;
        d.spirv = std::span<const std::uint32_t>(kDistributionTestSpv);
        d.bindings = {vk::DescriptorType::eUniformTexelBuffer, vk::DescriptorType::eStorageBuffer,
                      vk::DescriptorType::eStorageBuffer};
        d.pushConstantBytes = sizeof(Push);
        pipe = std::make_unique<ComputePipeline>(dev, d);
    }
    Push push = pushIn;
    push.count = std::uint32_t(items.size());
    GpuBuffer tab(dev, table.size() * 4, vk::BufferUsageFlagBits::eUniformTexelBuffer);
    tab.upload(table.data(), table.size() * 4);
    const vk::raii::BufferView view = tab.texelView(vk::Format::eR32Sfloat);
    GpuBuffer in(dev, items.size() * 16, vk::BufferUsageFlagBits::eStorageBuffer);
    GpuBuffer out(dev, items.size() * 32, vk::BufferUsageFlagBits::eStorageBuffer);
    in.upload(items.data(), items.size() * 16);
    pipe->bindTexelView(0, *view);
    pipe->bindBuffer(1, in.buffer());
    pipe->bindBuffer(2, out.buffer());
    dev.submitAndWait([&](vk::raii::CommandBuffer& cmd) {
        pipe->recordDispatch(cmd, (push.count + 63) / 64, 1, &push, sizeof push);
    });
    std::vector<Out> result(items.size());
    out.download(result.data(), result.size() * 32);
    dev.instance().throwIfValidationMessages("distribution test kernel");
    return result;
}

std::vector<glm::vec4> inputs(std::uint32_t seed, int n) {
    std::vector<glm::vec4> v;
    const float edges[] = {0.0f, 0x1p-24f, 0.25f, 0.5f, 0.75f, 0x1.fffffep-1f};
    for (float a : edges)
        for (float b : edges) v.emplace_back(a, b, 0.0f, 0.0f);
    UniformSource src(seed);
    for (int i = 0; i < n; ++i) {
        const glm::vec2 u = src.next2();
        v.emplace_back(u.x, u.y, 0.0f, 0.0f);
    }
    return v;
}

TEST(GpuDistribution, Distribution2DMatchesHostAndFitsPdf) {
    VKP_REQUIRE_DEVICE(dev);
    const std::uint32_t nu = 16, nv = 8;
    std::vector<double> w(nu * nv);
    UniformSource wsrc(3);
    for (double& x : w) x = wsrc.next() < 0.3f ? 0.0 : double(wsrc.next());
    w[5 * nu + 9] = 500.0;
    const std::vector<float> table = buildDistribution2D(w, nu, nv);
    const std::vector<glm::vec4> items = inputs(41, 20000);
    const std::vector<Out> dev0 = runKernel(dev, table, {0, 0, nu, nv, 1.0f, 0.0f}, items);
    int bad = 0;
    double worstPos = 0.0, worstInv = 0.0;
    std::vector<double> observed(4 * nu * nv, 0.0), expected(4 * nu * nv, 0.0);
    for (std::size_t i = 0; i < items.size(); ++i) {
        float pdf;
        const glm::vec2 u(items[i]);
        const glm::vec2 p = gpu::sampleDistribution2D(table.data(), 0u, nu, nv, u, pdf);
        const glm::vec2 inv = gpu::invertDistribution2D(table.data(), 0u, nu, nv, p);
        const Out& d = dev0[i];
        const double pos = std::max(std::abs(d.o0.x - p.x), std::abs(d.o0.y - p.y));
        const double ierr = std::max(std::abs(d.o1.x - inv.x), std::abs(d.o1.y - inv.y));
        worstPos = std::max(worstPos, pos);
        worstInv = std::max(worstInv, ierr);
        // Same cell, same density (bit for bit), the device's pdf alone equals its sample's pdf.
        const bool ok = pos < 1e-6 && ierr < 1e-6 && d.o0.z == pdf && d.o0.w == d.o0.z &&
                        gpu::distCellOf(d.o0.x, nu) == gpu::distCellOf(p.x, nu) &&
                        gpu::distCellOf(d.o0.y, nv) == gpu::distCellOf(p.y, nv);
        if (!ok && bad++ < 5)
            ADD_FAILURE() << "item " << i << " u " << u.x << "," << u.y << ": device " << d.o0.x << "," << d.o0.y
                          << " pdf " << d.o0.z << " host " << p.x << "," << p.y << " pdf " << pdf;
        if (i >= 36) {  // the uniform items only
            const int cx = std::min(int(d.o0.x * 2 * nu), int(2 * nu - 1)), cy = std::min(int(d.o0.y * 2 * nv), int(2 * nv - 1));
            observed[cy * 2 * nu + cx] += 1.0;
        }
    }
    std::printf("  device vs host: worst position difference %.3g, worst inverse difference %.3g\n", worstPos, worstInv);
    EXPECT_EQ(bad, 0);
    const double n = double(items.size() - 36);
    for (std::uint32_t cy = 0; cy < 2 * nv; ++cy)
        for (std::uint32_t cx = 0; cx < 2 * nu; ++cx) {
            const glm::vec2 c((cx + 0.5f) / (2 * nu), (cy + 0.5f) / (2 * nv));
            expected[cy * 2 * nu + cx] = n * gpu::pdfDistribution2D(table.data(), 0u, nu, nv, c) / (4.0 * nu * nv);
        }
    EXPECT_TRUE(passesChi2(chi2Test(observed, expected)));
}

TEST(GpuDistribution, EnvMapMatchesHostAndFitsPdf) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene;
    Image& img = scene.environment.image;
    img = Image(32, 16);
    for (std::uint32_t j = 0; j < 16; ++j)
        for (std::uint32_t i = 0; i < 32; ++i) img.set(i, j, 0.2f + 0.05f * float(i % 3), 0.3f, j == 9 ? 0.0f : 0.4f);
    img.set(20, 5, 300.0f, 200.0f, 100.0f);
    img.set(3, 0, 20.0f, 20.0f, 20.0f);
    const std::vector<float> table = packEnvironment(scene).distribution;
    const float rot = 0.6f;
    const glm::vec2 cs(std::cos(rot), std::sin(rot));
    const std::vector<glm::vec4> items = inputs(43, 20000);
    const std::vector<Out> d1 = runKernel(dev, table, {1, 0, 32, 16, cs.x, cs.y}, items);
    int bad = 0, flips = 0;
    double worstDir = 0.0, worstPdf = 0.0;
    std::vector<glm::dvec2> uvs;
    for (std::size_t i = 0; i < items.size(); ++i) {
        float pdf;
        glm::vec2 uv;
        const glm::vec3 dir = gpu::sampleEnvMap(table.data(), 32, 16, cs, glm::vec2(items[i]), pdf, uv);
        const Out& d = d1[i];
        const glm::vec3 ddir(d.o0);
        const double dirErr = glm::length(glm::dvec3(ddir - dir));
        worstDir = std::max(worstDir, dirErr);
        // The sample's texel is chosen by the binary search alone: equal in both builds.
        const bool sameTexel = gpu::envTexel(glm::vec2(d.o1.y, d.o1.z), 32, 16) == gpu::envTexel(uv, 32, 16);
        if (!sameTexel || dirErr > 4e-6) {
            if (bad++ < 5) ADD_FAILURE() << "item " << i << ": direction differs by " << dirErr;
            continue;
        }
        if (d.o0.w > 0.0f) uvs.emplace_back(gpu::envMapUV(ddir).x, gpu::envMapUV(ddir).y);
        // The pdf of the sample: the same density over sin(theta) from nearly the same direction.
        const double rel = pdf > 0.0f ? std::abs(double(d.o0.w) - pdf) / pdf : std::abs(d.o0.w);
        worstPdf = std::max(worstPdf, rel);
        if (rel > 1e-4 && bad++ < 5) ADD_FAILURE() << "item " << i << ": pdf " << d.o0.w << " host " << pdf;
        // pdfEnvMap alone finds the texel again from the direction: a flip when it lands next door.
        if (std::abs(double(d.o1.x) - d.o0.w) > 1e-4 * d.o0.w) ++flips;
    }
    std::printf("  device vs host: worst direction difference %.3g, worst relative pdf difference %.3g, %d texel-edge flips\n",
                worstDir, worstPdf, flips);
    EXPECT_EQ(bad, 0);
    EXPECT_LE(flips, 5);
    // Chi-square of the device's directions in the world's (u, v), as test_env_stats.cpp.
    Grid2D g;
    g.nx = 35;
    g.ny = 17;
    const Pdf2D pdfUV = [&](double u, double v) {
        const glm::vec3 dir = gpu::envMapDirection(glm::vec2(float(u), float(v)));
        return double(gpu::pdfEnvMap(table.data(), 32, 16, cs, dir)) * 2.0 * 9.869604401089358 * std::sin(3.141592653589793 * v);
    };
    EXPECT_TRUE(passesChi2(chi2Test2D(uvs, g, pdfUV)));
}

}  // namespace
}  // namespace vkp::test
