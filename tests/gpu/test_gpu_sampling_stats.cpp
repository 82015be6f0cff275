// Chi-square tests of the DEVICE's samples: the GLSL build of the shared sampling code
// (sampling_test.comp) draws cosine-hemisphere directions and quad, triangle and sphere light
// samples (cone, on-surface and inside strategies), which are fitted against the host's pdfs with
// the method of tests/stats (tests/support/chi2.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "gpu_env.h"
#include "sampling_kernel.h"
#include "shared/light_sampling.h"
#include "shared/triangle_sampling.h"
#include "stat_suite.h"

namespace vkp::test {
namespace {

namespace gpu = vkp::gpu;
using namespace sampling;
using glm::dvec3;

// ---- Chi-square tests of the device's samples ------------------------------------------------
// The host tests (tests/stats) fit the C++ build's samples; these fit the DEVICE's samples against
// the same (host) pdfs, with the same method (tests/support/chi2.h) and the same per-test level
// statsAlpha() (~7.85e-5, stat_suite.h). For correct code the 6 fits below falsely fail with
// probability <= 1 - (1 - statsAlpha())^6 ~ 4.7e-4 (the seeds are fixed: a build passes or fails
// always); they belong to the stats suite's budget of kStatsChi2Budget tests (family-wise 1%).
// The teeth test expects a rejection (p < 1e-6 for a grossly wrong pdf) and is not counted.

constexpr int kChi2Samples = 100000;

/// Directions sampled on the device by routine r from kChi2Samples uniform xi (make(xi) builds
/// the input); only valid samples (pdf at out0.w or out1.x > 0), at most 1e-4 invalid.
std::vector<dvec3> deviceDirections(VulkanDevice& dev, Routine r, std::uint32_t seed, const std::function<Item(vec2)>& make) {
    UniformSource rng(seed);
    std::vector<Item> items;
    for (int i = 0; i < kChi2Samples; ++i) items.push_back(make(rng.next2()));
    const std::vector<Out> out = runSamplingKernel(dev, r, items);
    std::vector<dvec3> dirs;
    int nonFinite = 0;
    for (const Out& o : out) {
        const float pdf = r == kCosineHemi ? o.o[0].w : o.o[1].x;
        if (!(std::isfinite(pdf) && std::isfinite(o.o[0].x) && std::isfinite(o.o[0].y) && std::isfinite(o.o[0].z))) ++nonFinite;
        if (pdf > 0.0f) dirs.emplace_back(xyz(o.o[0]));
    }
    EXPECT_EQ(nonFinite, 0);
    EXPECT_LE(kChi2Samples - int(dirs.size()), kChi2Samples / 10000) << "invalid samples";
    expectNoValidationMessages(dev);
    return dirs;
}

void expectFits(const std::vector<dvec3>& dirs, const SphereBinning& b, const PdfDir& pdf) {
    const std::vector<double> cells = integrateDirectionCells(b, pdf, 1e-4, 8, 1);
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));
}

TEST(GpuSamplingStats, CosineHemisphere) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dirs = deviceDirections(dev, kCosineHemi, 501, [](vec2 u) { return item(vec4(u, 0.0f, 0.0f)); });
    SphereBinning b;
    b.zMin = 0.0;
    b.nZ = 20;
    b.nPhi = 40;
    expectFits(dirs, b, [](const dvec3& d) { return double(gpu::pdfCosineHemisphere(float(d.z))); });
}

// Teeth: the same pipeline must reject samples of another distribution (cosine-weighted
// directions against the uniform hemisphere pdf), or the fits above would prove nothing.
TEST(GpuSamplingStats, TeethCosineSamplesAreNotUniform) {
    VKP_REQUIRE_DEVICE(dev);
    const auto dirs = deviceDirections(dev, kCosineHemi, 507, [](vec2 u) { return item(vec4(u, 0.0f, 0.0f)); });
    SphereBinning b;
    b.zMin = 0.0;
    b.nZ = 20;
    b.nPhi = 40;
    const Chi2Result r = chi2TestDirections(dirs, b, [](const dvec3& d) { return double(gpu::pdfUniformHemisphere(float(d.z))); });
    EXPECT_LT(r.pValue, 1e-6) << r.message;
}

/// A cap around the planar light's normal (oriented from p towards it) that contains the light
/// (widened by 5%); p must be above the light, so that the cap's pole hits it.
SphereBinning planarCap(const PlanarCase& pc, bool tri) {
    dvec3 n = glm::normalize(glm::cross(dvec3(pc.e1), dvec3(pc.e2)));
    if (glm::dot(n, dvec3(pc.q - pc.p)) < 0.0) n = -n;
    double zLo = 1.0;
    for (vec3 corner : {pc.q, pc.q + pc.e1, pc.q + pc.e2, pc.q + pc.e1 + pc.e2}) {
        if (tri && corner == pc.q + pc.e1 + pc.e2) continue;
        zLo = std::min(zLo, glm::dot(n, glm::normalize(dvec3(corner - pc.p))));
    }
    vec2 ab;
    EXPECT_LT(gpu::intersectParallelogram(pc.q, pc.e1, pc.e2, tri, pc.p, vec3(n), 0.0f, gpu::VKP_FAR, ab), gpu::VKP_FAR);
    return SphereBinning::around(n, zLo - 0.05 * (1.0 - zLo), 20, 40);
}

void expectPlanarFits(VulkanDevice& dev, const PlanarCase& pc, bool tri, std::uint32_t seed) {
    const auto dirs = deviceDirections(dev, tri ? kTriLight : kQuadLight, seed, [&](vec2 xi) {
        return item(vec4(pc.q, xi.x), vec4(pc.e1, xi.y), vec4(pc.e2, 0.0f), vec4(pc.p, 0.0f));
    });
    expectFits(dirs, planarCap(pc, tri), [&](const dvec3& d) {
        return double(tri ? gpu::pdfTriangleLight(pc.q, pc.e1, pc.e2, pc.p, vec3(d)) : gpu::pdfQuadLight(pc.q, pc.e1, pc.e2, pc.p, vec3(d)));
    });
}

TEST(GpuSamplingStats, QuadLight) {
    VKP_REQUIRE_DEVICE(dev);
    expectPlanarFits(dev, {{-1.0f, -0.5f, 2.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.2f, 0.1f, 1.7f}}, false, 502);
}

TEST(GpuSamplingStats, TriangleLight) {
    VKP_REQUIRE_DEVICE(dev);
    expectPlanarFits(dev, {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.2f}, {0.3f, 1.2f, 0.0f}, {0.5f, 0.3f, 0.6f}}, true, 503);
}

// The GLSL build of Arvo's spherical triangle sampling (triangle_sampling.h) from a point where it
// is used (S ~ 0.8 sr), fitted to its own pdf (1/S over the triangle).
TEST(GpuSamplingStats, SphericalTriangleLight) {
    VKP_REQUIRE_DEVICE(dev);
    const PlanarCase pc{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.2f}, {0.3f, 1.2f, 0.0f}, {0.5f, 0.3f, 0.6f}};
    ASSERT_TRUE(gpu::useSphericalTriangle(gpu::triangleLightSolidAngle(pc.q, pc.e1, pc.e2, pc.p)));
    const auto dirs = deviceDirections(dev, kSphTriLight, 504, [&](vec2 xi) {
        return item(vec4(pc.q, xi.x), vec4(pc.e1, xi.y), vec4(pc.e2, 0.0f), vec4(pc.p, 0.0f));
    });
    expectFits(dirs, planarCap(pc, true),
               [&](const dvec3& d) { return double(gpu::pdfTriangleLightSolidAngle(pc.q, pc.e1, pc.e2, pc.p, vec3(d), 0.0f)); });
}

void expectSphereFits(VulkanDevice& dev, const SphereCase& s, std::uint32_t expectedStrategy, std::uint32_t seed) {
    const double d = glm::length(dvec3(s.c) - dvec3(s.p));
    ASSERT_EQ(gpu::sphereLightStrategy(glm::length(s.c - s.p), s.R), expectedStrategy);
    const auto dirs = deviceDirections(dev, kSphereLight, seed, [&](vec2 xi) {
        return item(vec4(s.c, s.R), vec4(xi, 0.0f, 0.0f), vec4(0.0f), vec4(s.p, 0.0f));
    });
    const dvec3 axis = d > 0.0 ? (dvec3(s.c) - dvec3(s.p)) / d : dvec3(0.0, 0.0, 1.0);
    const double zMin = expectedStrategy == gpu::SPHERE_LIGHT_CONE ? std::cos(std::min(kPi, 1.1 * std::asin(s.R / d) + 1e-3)) : -1.0;
    expectFits(dirs, SphereBinning::around(axis, zMin, 20, 40),
               [&](const dvec3& w) { return double(gpu::pdfSphereLight(s.c, s.R, s.p, vec3(w))); });
}

const vec3 kSphereC(0.3f, -0.2f, 1.0f);

TEST(GpuSamplingStats, SphereLightCone) {
    VKP_REQUIRE_DEVICE(dev);
    expectSphereFits(dev, {kSphereC, 1.0f, kSphereC + vec3(0.0f, 1.5f, 0.0f)}, gpu::SPHERE_LIGHT_CONE, 504);
}

TEST(GpuSamplingStats, SphereLightOnSurface) {
    VKP_REQUIRE_DEVICE(dev);
    expectSphereFits(dev, {kSphereC, 1.5f, kSphereC + 1.5f * glm::normalize(vec3(1.0f, 2.0f, 3.0f))}, gpu::SPHERE_LIGHT_SURFACE, 505);
}

TEST(GpuSamplingStats, SphereLightInside) {
    VKP_REQUIRE_DEVICE(dev);
    expectSphereFits(dev, {kSphereC, 1.0f, kSphereC + vec3(0.4f, -0.3f, 0.2f)}, gpu::SPHERE_LIGHT_INSIDE, 506);
}

}  // namespace
}  // namespace vkp::test
