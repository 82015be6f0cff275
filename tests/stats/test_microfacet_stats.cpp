// Statistical and numerical tests of shaders/shared/microfacet.h (compiled as C++): the GGX
// visible-normal sampler and the sampler of the whole glTF BRDF, each as a sample/pdf pair:
//  (a) chi-square of the sampled directions against the pdf, for several (roughness, view angle)
//      pairs including grazing views and roughness 0 (alpha clamped to GGX_MIN_ALPHA);
//  (b) the pdf integrates to 1 over the sphere (adaptive quadrature, tests/support/chi2.h);
//  (c) the pdf the sampler returns with a sample equals the pdf function evaluated alone.
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed). This
// file performs 12 chi-square tests: for correct code they falsely fail together with probability
// <= 1 - (1 - statsAlpha())^12 ~ 9.4e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "shared/microfacet.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::dvec3;
using glm::vec2;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 200000;

/// Unit view direction at polar angle thetaDeg from the normal (+z), azimuth 0.3 rad.
vec3 viewAt(double thetaDeg) {
    const double t = thetaDeg * kPi / 180.0;
    return vec3(float(std::sin(t) * std::cos(0.3)), float(std::sin(t) * std::sin(0.3)), float(std::cos(t)));
}

/// A cap around the mirror direction of v wide enough for the specular lobe of alpha (the rest of
/// the sphere is in the binning's extra cells); the whole sphere for rough lobes.
SphereBinning lobeBinning(vec3 v, float alpha) {
    const dvec3 mirror(-v.x, -v.y, v.z);
    if (alpha > 0.15f) return SphereBinning::around(dvec3(0, 0, 1), -1.0, 30, 60);
    const double cap = std::min(kPi, 14.0 * double(alpha));
    return SphereBinning::around(mirror, std::cos(cap), 20, 40);
}

double sumOf(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s;
}

struct VndfCase {
    float roughness;
    double thetaDeg;
};

// (a), (b), (c) for the visible-normal sampler of the specular lobe.
TEST(MicrofacetStats, VndfSamplesFollowPdfAndPdfIntegratesToOne) {
    const VndfCase cases[] = {{1.0f, 0.0}, {0.5f, 45.0}, {0.5f, 89.0}, {0.3f, 75.0}, {0.1f, 30.0}, {0.0f, 60.0}};
    std::uint32_t seed = 701;
    for (const VndfCase& c : cases) {
        const float alpha = gpu::ggxAlpha(c.roughness);
        const vec3 v = viewAt(c.thetaDeg);
        SCOPED_TRACE("roughness " + std::to_string(c.roughness) + ", view " + std::to_string(c.thetaDeg) + " deg");
        UniformSource rng(seed++);
        std::vector<dvec3> dirs;
        double worstPdf = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            const vec2 u = rng.next2();
            const vec3 h = gpu::sampleGgxVisibleNormal(v, alpha, u);
            const vec3 l = gpu::sampleGgxVndf(v, alpha, u);
            ASSERT_TRUE(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z));
            ASSERT_NEAR(glm::length(l), 1.0f, 1e-5f);
            const float pHalf = gpu::pdfGgxVndfHalf(v, h, alpha), pAlone = gpu::pdfGgxVndf(v, l, alpha);
            ASSERT_GT(pHalf, 0.0f);
            worstPdf = std::max(worstPdf, std::fabs(double(pHalf) - pAlone) / pAlone);
            dirs.push_back(dvec3(l));
        }
        // (c) Measured worst relative difference 6.6e-5 (roughness 0: h rebuilt from v + l in float
        // moves by ~1e-7 rad, and D changes by ~4 theta dtheta / alpha^2 there).
        EXPECT_LT(worstPdf, 1e-3);
        const SphereBinning b = lobeBinning(v, alpha);
        const PdfDir pdf = [&](const dvec3& d) { return double(gpu::pdfGgxVndf(v, vec3(d), alpha)); };
        const std::vector<double> cells = integrateDirectionCells(b, pdf, 1e-5, 10, 1);
        std::printf("    roughness %.2f view %.1f: pdf integral %.6f, worst sample/alone pdf %.2e\n", c.roughness,
                    c.thetaDeg, sumOf(cells), worstPdf);
        EXPECT_NEAR(sumOf(cells), 1.0, 2e-3);                         // (b)
        EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));  // (a)
    }
}

struct BrdfCase {
    vec3 base;
    float metallic, roughness, specular;
    vec3 specularColor;
    double thetaDeg;
};

// (a), (b), (c) for the sampler of the whole BRDF (lobe choice + VNDF or cosine).
TEST(MicrofacetStats, GltfBrdfSamplesFollowPdfAndPdfIntegratesToOne) {
    const BrdfCase cases[] = {
        {vec3(1.0f), 0.0f, 1.0f, 1.0f, vec3(1.0f), 0.0},
        {vec3(0.8f, 0.3f, 0.1f), 0.0f, 0.4f, 1.0f, vec3(1.0f), 80.0},
        {vec3(0.9f, 0.6f, 0.3f), 0.5f, 0.3f, 0.7f, vec3(1.0f, 0.5f, 2.0f), 45.0},
        {vec3(0.5f), 0.0f, 0.1f, 1.0f, vec3(1.0f), 50.0},
        {vec3(0.9f, 0.8f, 0.7f), 1.0f, 0.6f, 1.0f, vec3(1.0f), 88.0},
        {vec3(0.2f), 0.3f, 0.0f, 1.0f, vec3(1.0f), 20.0},
    };
    std::uint32_t seed = 711;
    for (const BrdfCase& c : cases) {
        const gpu::GltfBrdf m = gpu::makeGltfBrdf(c.base, c.metallic, c.roughness, c.specular, c.specularColor);
        const vec3 v = viewAt(c.thetaDeg);
        SCOPED_TRACE("metallic " + std::to_string(c.metallic) + ", roughness " + std::to_string(c.roughness) +
                     ", view " + std::to_string(c.thetaDeg) + " deg");
        UniformSource rng(seed++);
        std::vector<dvec3> dirs;
        double worstPdf = 0.0;
        for (int i = 0; i < kSamples; ++i) {
            float pdf = -1.0f;
            const vec3 l = gpu::sampleGltfBrdf(m, v, rng.next3(), pdf);
            ASSERT_TRUE(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(pdf));
            ASSERT_GT(pdf, 0.0f);
            const float alone = gpu::pdfGltfBrdf(m, v, l);
            worstPdf = std::max(worstPdf, std::fabs(double(pdf) - alone) / alone);
            dirs.push_back(dvec3(l));
        }
        EXPECT_LT(worstPdf, 1e-3);  // (c), as for the VNDF above
        // A low roughness lobe is binned around the mirror direction, the diffuse lobe then falls
        // into the rest-of-sphere cells.
        const SphereBinning b = lobeBinning(v, m.alpha);
        const PdfDir pdf = [&](const dvec3& d) { return double(gpu::pdfGltfBrdf(m, v, vec3(d))); };
        const std::vector<double> cells = integrateDirectionCells(b, pdf, 1e-5, 10, 1);
        std::printf("    base %.1f,%.1f,%.1f metallic %.1f roughness %.1f view %.1f: P(specular) %.3f, pdf integral %.6f\n",
                    c.base.x, c.base.y, c.base.z, c.metallic, c.roughness, c.thetaDeg,
                    gpu::gltfSpecularProbability(m, v), sumOf(cells));
        EXPECT_NEAR(sumOf(cells), 1.0, 2e-3);                         // (b)
        EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));  // (a)
    }
}

// Teeth (not counted in the budget): VNDF samples against the pdf of another roughness must be
// rejected, or the fits above would prove little.
TEST(MicrofacetStats, TeethWrongRoughnessIsRejected) {
    const vec3 v = viewAt(40.0);
    UniformSource rng(731);
    std::vector<dvec3> dirs;
    for (int i = 0; i < kSamples; ++i) dirs.push_back(dvec3(gpu::sampleGgxVndf(v, gpu::ggxAlpha(0.5f), rng.next2())));
    const float wrong = gpu::ggxAlpha(0.55f);
    const SphereBinning b = lobeBinning(v, wrong);
    const Chi2Result r = chi2TestDirections(dirs, b, [&](const dvec3& d) { return double(gpu::pdfGgxVndf(v, vec3(d), wrong)); });
    EXPECT_LT(r.pValue, 1e-6) << r.message;
}

}  // namespace
