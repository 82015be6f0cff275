// The clear coat and sheen over the glTF BRDF (shaders/shared/layers.h, compiled as C++):
//  (a) the Charlie sheen distribution is normalised: int D(h) cos(theta_h) dh = 1;
//  (b) the sheen albedo table (host/render/sheen_albedo_table.cpp) agrees with a finer quadrature;
//  (c) white furnace: the layered material's directional albedo is at most 1 for white bases,
//      coats and sheens at every roughness and view angle up to 89.9 degrees, and a coat or sheen
//      over a white base loses little (lower bounds below, measured);
//  (d) f is reciprocal (same frame for coat and base);
//  (e) sampleLayered against pdfLayered: chi-square, the pdf integrates to 1 over the sphere, and the
//      pdf returned with a sample equals the pdf alone; also with a coat normal tilted away from
//      the shading normal;
//  (f) no NaN or Inf on a grid of directions including the horizon and below it.
// Significance: 6 chi-square tests at statsAlpha() (stat_suite.h): for correct code they falsely
// fail together with probability <= 1 - (1 - statsAlpha())^6 ~ 4.7e-4. The furnace bounds are
// one-sided at 5 standard errors + 1e-5 (32 tests: a false failure has probability < 1e-5).
// Seeds are fixed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/ggx_albedo_table.h"
#include "render/sheen_albedo_table.h"
#include "shared/layers.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::dvec3;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;

vec3 viewAt(double thetaDeg, double phi = 0.3) {
    const double t = thetaDeg * kPi / 180.0;
    return vec3(float(std::sin(t) * std::cos(phi)), float(std::sin(t) * std::sin(phi)), float(std::cos(t)));
}

gpu::Onb frameZ() { return gpu::onbFromNormal(vec3(0.0f, 0.0f, 1.0f)); }

gpu::LayeredBrdf layered(vec3 base, float metallic, float roughness, float specular, float coat, float coatRoughness,
                         vec3 sheen, float sheenRoughness, vec3 coatNormal = vec3(0.0f, 0.0f, 1.0f)) {
    gpu::LayeredBrdf m;
    m.base = gpu::makeGltfBrdf(base, metallic, roughness, specular, vec3(1.0f));
    m.layers = gpu::makeGltfLayers(coat, coatRoughness, sheen, sheenRoughness);
    m.frame = frameZ();
    m.coatFrame = gpu::onbFromNormal(glm::normalize(coatNormal));
    return m;
}

double sumOf(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s;
}

// (a) int D(h) cos(theta_h) dh over the hemisphere, by the midpoint rule in (cos^2-substituted
// theta, phi is trivial): 2 pi int_0^1 D(z) z dz with z = cos theta_h, refined near z = 0 where a
// small alpha puts the lobe.
TEST(LayersStats, CharlieDistributionIsNormalised) {
    for (float roughness : {0.05f, 0.2f, 0.5f, 0.8f, 1.0f}) {
        const float alpha = gpu::sheenAlpha(roughness);
        const int n = 200000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double t = (i + 0.5) / n, z = t * t;  // z = cos theta_h, dz = 2 t dt
            const double s = std::sqrt(1.0 - z * z);
            sum += double(gpu::charlieD(vec3(float(s), 0.0f, float(z)), alpha)) * z * 2.0 * t / n;
        }
        const double integral = 2.0 * kPi * sum;
        std::printf("    sheen roughness %.2f: int D cos = %.6f\n", roughness, integral);
        EXPECT_NEAR(integral, 1.0, 2e-3) << "roughness " << roughness;
    }
}

// (b) The table against a quadrature 4x finer in each direction, at table nodes.
TEST(LayersStats, SheenAlbedoTableMatchesAFinerQuadrature) {
    double worst = 0.0;
    for (int j : {0, 5, 16, 31}) {
        for (int i : {1, 8, 20, 31}) {
            const double s4 = double(i) / double(gpu::SHEEN_ALBEDO_N - 1), mu = s4 * s4 * s4 * s4;
            const float alpha = gpu::sheenAlpha(float(j) / float(gpu::SHEEN_ALBEDO_N - 1));
            const vec3 v(float(std::sqrt(1.0 - mu * mu)), 0.0f, float(mu));
            const int nt = 256, nphi = 256;
            double sum = 0.0;
            for (int a = 0; a < nt; ++a) {
                const double t = (a + 0.5) / nt, c = t * t, s = std::sqrt(std::max(0.0, 1.0 - c * c));
                for (int k = 0; k < nphi; ++k) {
                    const double phi = kPi * (k + 0.5) / nphi;
                    const vec3 l(float(s * std::cos(phi)), float(s * std::sin(phi)), float(c));
                    sum += double(gpu::sheenLobe(v, l, alpha)) * c * (kPi / nphi) * (2.0 * t) / nt;
                }
            }
            const double fine = 2.0 * sum;
            const double table = vkp::sheenAlbedoTable()[std::size_t(j) * gpu::SHEEN_ALBEDO_N + std::size_t(i)].x;
            // 2e-3, relative where E_s exceeds 1 (8.19 at mu = 1e-6 and roughness 0).
            worst = std::max(worst, std::abs(table - fine) / std::max(1.0, fine));
            EXPECT_NEAR(table, fine, 2e-3 * std::max(1.0, fine)) << "mu " << mu << " roughness index " << j;
        }
    }
    std::printf("    worst |table - fine quadrature| / max(1, E) %.2e\n", worst);
}

struct Albedo {
    double mean = 0.0, se = 0.0;
};

/// Directional albedo (green channel) of m seen from v with n samples of its own sampler.
Albedo albedo(const gpu::LayeredBrdf& m, vec3 v, int n, std::uint32_t seed, int& nonFinite) {
    UniformSource rng(seed);
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
        float pdf = 0.0f;
        const vec3 l = gpu::sampleLayered(m, v, rng.next3(), pdf);
        double w = 0.0;
        if (pdf > 0.0f) w = double(gpu::evalLayeredCos(m, v, l).y) / pdf;
        if (!std::isfinite(w) || w < 0.0) {
            ++nonFinite;
            continue;
        }
        s += w;
        s2 += w * w;
    }
    Albedo a;
    a.mean = s / n;
    a.se = std::sqrt(std::max(0.0, s2 / n - a.mean * a.mean) / (n - 1));
    return a;
}

struct FurnaceCase {
    const char* name;
    float metallic, roughness, specular, coat, coatRoughness, sheen, sheenRoughness;
    double lowest;  ///< the albedo may not fall below this up to 85 deg (measured minimum 0.954, 0.989, 0.884, 0.917, less ~0.03)
};

// (c) 4 materials x 8 view angles = 32 one-sided "albedo <= 1" tests, plus their lower bounds.
TEST(LayersStats, WhiteFurnaceStaysAtOrBelowOne) {
    const FurnaceCase cases[] = {
        // A coat over a white Lambertian base (specular 0): the coat reflects E_c, the base the rest
        // of what the min() passes on.
        {"coat over white diffuse", 0.0f, 1.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 0.92},
        {"rough coat over white dielectric", 0.0f, 0.5f, 1.0f, 1.0f, 0.6f, 0.0f, 1.0f, 0.96},
        {"sheen over white diffuse", 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.5f, 0.85},
        {"coat and sheen over white metal", 1.0f, 0.3f, 1.0f, 1.0f, 0.2f, 1.0f, 0.8f, 0.88},
    };
    const double angles[] = {0.0, 30.0, 50.0, 65.0, 75.0, 85.0, 89.0, 89.9};
    std::uint32_t seed = 901;
    for (const FurnaceCase& c : cases) {
        const gpu::LayeredBrdf m = layered(vec3(1.0f), c.metallic, c.roughness, c.specular, c.coat, c.coatRoughness,
                                           vec3(c.sheen), c.sheenRoughness);
        std::printf("    %-34s", c.name);
        for (double theta : angles) {
            int nonFinite = 0;
            const Albedo a = albedo(m, viewAt(theta), 100000, seed++, nonFinite);
            std::printf(" %.3f", a.mean);
            EXPECT_EQ(nonFinite, 0) << c.name << " at " << theta;
            EXPECT_LE(a.mean, 1.0 + 5.0 * a.se + 1e-5) << c.name << " at " << theta << " deg";
            if (theta <= 85.0) EXPECT_GE(a.mean, c.lowest) << c.name << " at " << theta << " deg";
        }
        std::printf("\n");
    }
}

// (d) f(v, l) = f(l, v) with the coat in the base's frame (f = evalLayeredCos / cos theta_l).
TEST(LayersStats, LayeredBrdfIsReciprocal) {
    const gpu::LayeredBrdf m = layered(vec3(0.7f, 0.5f, 0.3f), 0.3f, 0.4f, 1.0f, 0.8f, 0.2f, vec3(0.6f, 0.4f, 0.9f), 0.5f);
    double worst = 0.0;
    for (double tv : {5.0, 30.0, 60.0, 85.0})
        for (double tl : {10.0, 45.0, 70.0, 88.0})
            for (double phi : {0.0, 1.0, 2.5, 3.1}) {
                const vec3 v = viewAt(tv, 0.0), l = viewAt(tl, phi);
                const double a = double(gpu::evalLayeredCos(m, v, l).x) / l.z;
                const double b = double(gpu::evalLayeredCos(m, l, v).x) / v.z;
                worst = std::max(worst, std::abs(a - b) / std::max(std::abs(a), 1e-6));
            }
    std::printf("    worst relative |f(v,l) - f(l,v)| %.2e\n", worst);
    EXPECT_LT(worst, 1e-4);
}

struct SampleCase {
    vec3 base;
    float metallic, roughness, coat, coatRoughness;
    vec3 sheen;
    float sheenRoughness;
    double thetaDeg;
    vec3 coatNormal;
};

// (e) Chi-square, pdf integral and sample/alone pdf for six layered materials.
TEST(LayersStats, LayeredSamplesFollowPdfAndPdfIntegratesToOne) {
    const SampleCase cases[] = {
        {vec3(0.8f), 0.0f, 0.8f, 1.0f, 0.3f, vec3(0.0f), 0.0f, 20.0, vec3(0, 0, 1)},
        {vec3(0.5f, 0.2f, 0.1f), 0.0f, 0.5f, 0.0f, 0.0f, vec3(0.9f, 0.8f, 0.7f), 0.6f, 60.0, vec3(0, 0, 1)},
        {vec3(0.9f, 0.7f, 0.4f), 1.0f, 0.4f, 1.0f, 0.5f, vec3(0.5f), 0.3f, 75.0, vec3(0, 0, 1)},
        {vec3(0.3f), 0.0f, 1.0f, 0.6f, 0.8f, vec3(1.0f), 1.0f, 45.0, vec3(0, 0, 1)},
        {vec3(0.6f), 0.0f, 0.6f, 1.0f, 0.4f, vec3(0.0f), 0.0f, 35.0, vec3(0.3f, 0.1f, 1.0f)},  // tilted coat normal
        {vec3(0.2f, 0.4f, 0.8f), 0.5f, 0.2f, 0.5f, 0.6f, vec3(0.3f, 0.6f, 0.2f), 0.8f, 85.0, vec3(-0.2f, 0.2f, 1.0f)},
    };
    std::uint32_t seed = 931;
    for (const SampleCase& c : cases) {
        const gpu::LayeredBrdf m = layered(c.base, c.metallic, c.roughness, 1.0f, c.coat, c.coatRoughness, c.sheen,
                                           c.sheenRoughness, c.coatNormal);
        const vec3 v = viewAt(c.thetaDeg);
        SCOPED_TRACE("case with view " + std::to_string(c.thetaDeg) + " deg");
        UniformSource rng(seed++);
        std::vector<dvec3> dirs;
        double worstPdf = 0.0;
        for (int i = 0; i < 200000; ++i) {
            float pdf = -1.0f;
            const vec3 l = gpu::sampleLayered(m, v, rng.next3(), pdf);
            ASSERT_TRUE(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(pdf));
            ASSERT_NEAR(glm::length(l), 1.0f, 1e-4f);
            ASSERT_GT(pdf, 0.0f);
            const float alone = gpu::pdfLayered(m, v, l);
            worstPdf = std::max(worstPdf, std::fabs(double(pdf) - alone) / alone);
            dirs.push_back(dvec3(l));
        }
        EXPECT_LT(worstPdf, 1e-5);  // sampleLayered returns pdfLayered itself
        const SphereBinning b = SphereBinning::around(dvec3(0, 0, 1), -1.0, 30, 60);
        const PdfDir pdf = [&](const dvec3& d) { return double(gpu::pdfLayered(m, v, vec3(d))); };
        const std::vector<double> cells = integrateDirectionCells(b, pdf, 1e-5, 10, 1);
        const vec3 p = gpu::layerProbabilities(m, v);
        std::printf("    view %.0f: P(coat, sheen, base) = %.3f %.3f %.3f, pdf integral %.6f\n", c.thetaDeg, p.x, p.y, p.z,
                    sumOf(cells));
        EXPECT_NEAR(sumOf(cells), 1.0, 2e-3);
        EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));
    }
}

// (f) eval, pdf and sample stay finite on a grid including grazing, horizon and below-surface
// directions, roughness 0 for every lobe.
TEST(LayersStats, NoNonFiniteValues) {
    const gpu::LayeredBrdf ms[] = {
        layered(vec3(1.0f), 0.0f, 0.0f, 1.0f, 1.0f, 0.0f, vec3(1.0f), 0.0f),
        layered(vec3(0.5f), 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, vec3(1.0f), 1.0f, vec3(0.5f, 0.0f, 1.0f)),
    };
    int bad = 0;
    for (const gpu::LayeredBrdf& m : ms)
        for (double tv : {0.0, 45.0, 89.99, 90.0, 120.0})
            for (double tl : {0.0, 30.0, 89.99, 90.0, 135.0, 180.0})
                for (double phi : {0.0, 1.5, 3.14159}) {
                    const vec3 v = viewAt(tv, 0.0), l = viewAt(tl, phi);
                    const vec3 f = gpu::evalLayeredCos(m, v, l);
                    const float p = gpu::pdfLayered(m, v, l);
                    float ps = 0.0f;
                    const vec3 s = gpu::sampleLayered(m, v, vec3(0.37f, 0.61f, 0.18f), ps);
                    if (!std::isfinite(f.x + f.y + f.z) || !std::isfinite(p) || !std::isfinite(s.x + s.y + s.z) ||
                        !std::isfinite(ps) || f.x < 0.0f || p < 0.0f)
                        ++bad;
                }
    EXPECT_EQ(bad, 0);
}

}  // namespace
