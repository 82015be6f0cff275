// The GLSL build of shaders/shared/microfacet.h (routines 16-18 of shaders/tests/sampling_test.comp)
// against its C++ build, and chi-square fits of the DEVICE's samples:
//  - GGX visible-normal sampling: normal and reflected direction equal the host's sample, the pdfs
//    equal the host's pdf evaluated at the device's sample;
//  - the sampler of the whole glTF BRDF: direction, returned pdf, pdfGltfBrdf, lobe probability;
//  - eval: f, pdf, V, G1, D for pairs of directions including grazing ones and ones below the surface;
//  - no NaN or Inf output, for roughness 0 (alpha = GGX_MIN_ALPHA) to 1 and grazing views.
// Tolerances: each is stated at its comparison, ~10x the largest difference measured on lavapipe
// (printed as "worst error/tolerance").
// Chi-square: 3 fits at statsAlpha() (~7.85e-5, stat_suite.h), counted in the stats suite's budget
// of kStatsChi2Budget; for correct code they falsely fail together with probability <= 2.4e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "gpu_env.h"
#include "sampling_kernel.h"
#include "shared/microfacet.h"
#include "stat_suite.h"

namespace vkp::test {
namespace {

namespace gpu = vkp::gpu;
using namespace sampling;
using glm::dvec3;

/// Local view directions: the pole, grazing ones (89, 89.9, 89.999 degrees), then uniform.
std::vector<vec3> views(std::uint32_t seed, int n) {
    std::vector<vec3> out;
    for (double deg : {0.0, 30.0, 60.0, 85.0, 89.0, 89.9, 89.999}) {
        const double t = deg * kPi / 180.0;
        out.push_back(vec3(float(std::sin(t) * 0.6), float(std::sin(t) * 0.8), float(std::cos(t))));
    }
    UniformSource rng(seed);
    for (int i = 0; i < n; ++i) out.push_back(gpu::sampleUniformHemisphere(rng.next2()));
    return out;
}

const float kRoughness[] = {0.0f, 0.01f, 0.05f, 0.2f, 0.5f, 1.0f};

/// Tolerance of a visible normal (and its reflection) sampled from u: Heitz's listing takes
/// sqrt(1 - p1^2 - p2^2) with p1^2 + p2^2 -> 1 as u.x -> 1, which multiplies the ~1 ulp
/// differences of sin/cos by ~1 / sqrt(1 - u.x) (seen: 1.5e-5 at u.x = 0.994).
double vndfDirTol(double ux) { return kDirTol * (1.0 + 1.0 / std::sqrt(std::max(1.0 - ux, 1e-12))); }

/// Largest component difference of two directions.
double dirDiff(const vec4& a, const vec4& b) {
    return std::max({std::fabs(double(a.x) - b.x), std::fabs(double(a.y) - b.y), std::fabs(double(a.z) - b.z)});
}

TEST(GpuSamplingMicrofacet, VndfMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const std::vector<vec2> us = uPairs(901, kRandomItems / 2);
    const std::vector<vec3> vs = views(902, kRandomItems / 2);
    for (std::size_t i = 0; i < us.size(); ++i) {
        const float alpha = gpu::ggxAlpha(kRoughness[i % 6]);
        items.push_back(item(vec4(vs[i % vs.size()], alpha), vec4(us[i], 0.0f, 0.0f)));
    }
    checkRoutine(dev, kGgxVndf, "ggx vndf", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const vec3 v = xyz(it.in[0]), l = xyz(d.o[0]), m = xyz(d.o[1]);
        const float alpha = it.in[0].w;
        // Directions: built with sin/cos, sqrt and two normalize(): vndfDirTol.
        for (int k = 0; k < 3; ++k) {
            c.near("normal", d.o[1][k], h.o[1][k], vndfDirTol(it.in[1].x));
            c.near("direction", d.o[0][k], h.o[0][k], 2.0 * vndfDirTol(it.in[1].x));
        }
        // pdfs evaluated at the device's sample: D of a half vector rebuilt from v + l in float
        // (pdfGgxVndf) differs by up to ~4 theta dtheta / alpha^2 per ulp of h near the clamp.
        c.near("pdf(l)", d.o[0].w, gpu::pdfGgxVndf(v, l, alpha), 1e-9, 1e-4);
        c.near("pdf(h)", d.o[1].w, gpu::pdfGgxVndfHalf(v, m, alpha), 1e-9, 1e-5);
    });
}

/// A random glTF material (or one of the corner cases) in the item layout of routines 17 and 18.
Item materialItem(UniformSource& rng, std::size_t i, vec3 v, vec3 w) {
    vec3 base = rng.next3();
    float metallic = rng.next(), roughness = kRoughness[i % 6], spec = rng.next();
    const vec3 specColor = 2.0f * rng.next3();
    if (i % 7 == 0) metallic = 0.0f;
    if (i % 7 == 1) metallic = 1.0f;
    if (i % 7 == 2) spec = 0.0f;
    if (i % 7 == 3) base = vec3(0.0f);
    return item(vec4(base, metallic), vec4(specColor, spec), vec4(roughness, w), vec4(v, 0.0f));
}

TEST(GpuSamplingMicrofacet, GltfBrdfSampleMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    UniformSource rng(911);
    const std::vector<vec3> vs = views(912, kRandomItems);
    for (std::size_t i = 0; i < vs.size(); ++i) items.push_back(materialItem(rng, i, vs[i], rng.next3()));
    checkRoutine(dev, kGltfSample, "gltf brdf sample", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const gpu::GltfBrdf b = gpu::makeGltfBrdf(xyz(it.in[0]), it.in[0].w, it.in[2].x, it.in[1].w, xyz(it.in[1]));
        const vec3 v = xyz(it.in[3]), l = xyz(d.o[0]);
        c.near("P(specular)", d.o[1].y, h.o[1].y, 1e-6);
        c.bitsEqual("alpha", d.o[1].z, h.o[1].z);
        if (std::fabs(it.in[2].y - h.o[1].y) < 1e-5) {  // u at the lobe threshold: either lobe is right
            c.flip();
            return;
        }
        for (int k = 0; k < 3; ++k) c.near("direction", d.o[0][k], h.o[0][k], 2.0 * vndfDirTol(it.in[2].z));
        // The pdf returned with the sample comes from the sampled half vector: compared with the
        // host's returned pdf. D's relative change per radian of h is at most 2 / alpha (at
        // theta_h = alpha), and h moves by at most the samples' difference plus the 2 ulps that
        // rounding l may hide (seen: 2e-5 relative with identical l at alpha = 1e-3).
        c.near("pdf returned", d.o[0].w, h.o[0].w, 1e-9, 1e-5 + 2.0 / b.alpha * (dirDiff(d.o[0], h.o[0]) + 1.2e-7));
        // pdfGltfBrdf at the device's direction, evaluated by both builds: rounding only.
        c.near("pdf alone", d.o[1].x, gpu::pdfGltfBrdf(b, v, l), 1e-9, 1e-5);
    });
}

TEST(GpuSamplingMicrofacet, GltfBrdfEvalMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    UniformSource rng(921);
    const std::vector<vec3> vs = views(922, kRandomItems);
    for (std::size_t i = 0; i < vs.size(); ++i) {
        // l: a mirror of v (the peak of the lobe), uniform on the sphere (half of them below), or v.
        vec3 l = gpu::sampleUniformSphere(rng.next2());
        if (i % 5 == 0) l = vec3(-vs[i].x, -vs[i].y, vs[i].z);
        if (i % 5 == 1) l = vs[i];
        items.push_back(materialItem(rng, i, vs[i], l));
    }
    checkRoutine(dev, kGltfEval, "gltf brdf eval", items, [](Compare& c, const Item&, const Out& d, const Out& h) {
        // Same inputs on both sides: only the rounding of sqrt, division and the (1 - c)^5 chain.
        // f and D at the peak of a 1e-3 lobe reach ~3e5: relative tolerances.
        for (int k = 0; k < 3; ++k) c.near("f", d.o[0][k], h.o[0][k], 1e-7, 1e-5);
        c.near("pdf", d.o[0].w, h.o[0].w, 1e-7, 1e-5);
        c.near("V", d.o[1].x, h.o[1].x, 1e-7, 1e-5);
        c.near("G1", d.o[1].y, h.o[1].y, 1e-7, 1e-6);
        c.near("D", d.o[1].z, h.o[1].z, 1e-7, 1e-5);
    });
}

// ---- Chi-square fits of the device's samples ------------------------------------------------

constexpr int kChi2Samples = 200000;

void expectDeviceFit(VulkanDevice& dev, Routine r, std::uint32_t seed, const std::function<Item(vec3)>& make,
                     const SphereBinning& b, const PdfDir& pdf) {
    UniformSource rng(seed);
    std::vector<Item> items;
    for (int i = 0; i < kChi2Samples; ++i) items.push_back(make(rng.next3()));
    const std::vector<Out> out = runSamplingKernel(dev, r, items);
    std::vector<dvec3> dirs;
    for (const Out& o : out) {
        ASSERT_TRUE(std::isfinite(o.o[0].x) && std::isfinite(o.o[0].y) && std::isfinite(o.o[0].z) && std::isfinite(o.o[0].w));
        dirs.emplace_back(xyz(o.o[0]));
    }
    expectNoValidationMessages(dev);
    const std::vector<double> cells = integrateDirectionCells(b, pdf, 1e-5, 10, 1);
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));
}

vec3 viewAt(double deg) {
    const double t = deg * kPi / 180.0;
    return vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

TEST(GpuSamplingMicrofacet, DeviceVndfSamplesFitPdf) {
    VKP_REQUIRE_DEVICE(dev);
    {  // rough, 60 degrees: binned over the whole sphere
        const vec3 v = viewAt(60.0);
        const float alpha = gpu::ggxAlpha(0.5f);
        expectDeviceFit(dev, kGgxVndf, 931, [&](vec3 u) { return item(vec4(v, alpha), vec4(u.x, u.y, 0.0f, 0.0f)); },
                        SphereBinning::around(dvec3(0, 0, 1), -1.0, 30, 60),
                        [&](const dvec3& d) { return double(gpu::pdfGgxVndf(v, vec3(d), alpha)); });
    }
    {  // near specular at a grazing 80 degrees: a cap of 14 alpha around the mirror direction
        const vec3 v = viewAt(80.0);
        const float alpha = gpu::ggxAlpha(0.05f);
        expectDeviceFit(dev, kGgxVndf, 932, [&](vec3 u) { return item(vec4(v, alpha), vec4(u.x, u.y, 0.0f, 0.0f)); },
                        SphereBinning::around(dvec3(-v.x, -v.y, v.z), std::cos(14.0 * alpha), 20, 40),
                        [&](const dvec3& d) { return double(gpu::pdfGgxVndf(v, vec3(d), alpha)); });
    }
}

TEST(GpuSamplingMicrofacet, DeviceGltfBrdfSamplesFitPdf) {
    VKP_REQUIRE_DEVICE(dev);
    const vec3 v = viewAt(70.0), base(0.8f, 0.5f, 0.2f);
    const gpu::GltfBrdf b = gpu::makeGltfBrdf(base, 0.3f, 0.4f, 1.0f, vec3(1.0f));
    expectDeviceFit(dev, kGltfSample, 933,
                    [&](vec3 u) { return item(vec4(base, 0.3f), vec4(1.0f, 1.0f, 1.0f, 1.0f), vec4(0.4f, u), vec4(v, 0.0f)); },
                    SphereBinning::around(dvec3(0, 0, 1), -1.0, 30, 60),
                    [&](const dvec3& d) { return double(gpu::pdfGltfBrdf(b, v, vec3(d))); });
}

}  // namespace
}  // namespace vkp::test
