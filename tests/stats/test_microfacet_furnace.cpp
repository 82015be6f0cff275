// Energy and robustness of the glTF BRDF (shaders/shared/microfacet.h, compiled as C++):
//  - white furnace: the directional albedo a(v) = integral of f(v, l) cos(theta_l) dl for base
//    colour 1, metallic 0 and 1, roughness 0 .. 1 and view angles up to 89.9 degrees is at most 1
//    (Monte Carlo with the BRDF's own sampler, fixed seed, tolerance in standard errors below);
//  - the GGX D is normalised (integral of D(h) cos(theta_h) = 1), f is reciprocal, and
//    specularFactor 0 with metallic 0 is exactly the Lambertian base colour / pi;
//  - no NaN or Inf from eval, pdf or sample for any pair of directions on a grid that includes
//    the horizon, directions below it and roughness 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "shared/microfacet.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::vec2;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;

vec3 viewAt(double thetaDeg) {
    const double t = thetaDeg * kPi / 180.0;
    return vec3(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

struct Albedo {
    double mean = 0.0, se = 0.0;
};

/// Directional albedo (green channel: white base makes all equal) of m seen from v with n samples
/// of the BRDF's own sampler: the mean of f cos / pdf (0 for directions below the surface).
Albedo albedo(const gpu::GltfBrdf& m, vec3 v, int n, std::uint32_t seed, int& nonFinite) {
    UniformSource rng(seed);
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
        float pdf = 0.0f;
        const vec3 l = gpu::sampleGltfBrdf(m, v, rng.next3(), pdf);
        double w = 0.0;
        if (l.z > 0.0f && pdf > 0.0f) w = double(gpu::evalGltfBrdf(m, v, l).y) * l.z / pdf;
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

// White furnace. 2 x 8 x 7 = 112 one-sided tests "albedo <= 1": each fails if the estimate exceeds
// 1 by more than 5 standard errors + 1e-5 (the 1e-5 covers float rounding of weights that are
// exactly 1 in exact arithmetic: the Lambertian and the smooth metal at normal incidence, where
// the variance is 0). For a BRDF with albedo <= 1 the family falsely fails with probability
// <= 112 * P(Z > 5) = 112 * 2.9e-7 = 3.2e-5 (normal approximation of a mean of 50000 bounded
// weights: f cos / pdf <= base part / (1 - P(specular)) + specular part / P(specular) <= 20).
// Measured: largest albedo 1.0020 (metallic 0, roughness 0.02, normal incidence, +1.5 se).
TEST(MicrofacetFurnace, WhiteFurnaceAlbedoAtMostOne) {
    const float roughness[] = {0.0f, 0.02f, 0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
    const double views[] = {0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9};
    const int n = 50000;
    int nonFinite = 0;
    std::uint32_t seed = 801;
    double worst = 0.0;
    for (float metallic : {0.0f, 1.0f}) {
        std::printf("    metallic %.0f: albedo per roughness (rows) and view angle (columns %g..%g deg)\n", metallic,
                    views[0], views[6]);
        for (float r : roughness) {
            const gpu::GltfBrdf m = gpu::makeGltfBrdf(vec3(1.0f), metallic, r, 1.0f, vec3(1.0f));
            std::printf("      r %.2f:", r);
            for (double th : views) {
                const Albedo a = albedo(m, viewAt(th), n, seed++, nonFinite);
                std::printf(" %.4f", a.mean);
                worst = std::max(worst, a.mean);
                EXPECT_LE(a.mean, 1.0 + 5.0 * a.se + 1e-5) << "metallic " << metallic << " roughness " << r << " view " << th
                                                           << ": albedo " << a.mean << " +- " << a.se;
            }
            std::printf("\n");
        }
    }
    std::printf("    largest albedo %.5f\n", worst);
    EXPECT_EQ(nonFinite, 0);
}

// Energy conservation of the layered dielectric (microfacet.h: the base weighted by the energy the
// specular layer leaves, Kulla and Conty 2017): a white base under the default specular layer
// (metallic 0, f0 0.04, f90 1) reflects all the light at every angle and roughness. Tolerance: 5
// standard errors + 0.3% for the albedo table's interpolation (its worst error against brute-force
// integration on a 10 x 10 grid of roughness and angle: 0.23%, at roughness 0 and 89.5 degrees).
// 56 two-sided tests at 5 se: family-wise false failure <= 56 * 5.7e-7 = 3.2e-5.
// Before the table (base weighted by 1 - F(n.v)) this read 0.41 at 85 degrees, roughness 1.
TEST(MicrofacetFurnace, WhiteDielectricReflectsAllTheLight) {
    const float roughness[] = {0.0f, 0.02f, 0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
    const double views[] = {0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9};
    int nonFinite = 0;
    std::uint32_t seed = 901;
    double lo = 2.0, hi = 0.0;
    for (float r : roughness) {
        const gpu::GltfBrdf m = gpu::makeGltfBrdf(vec3(1.0f), 0.0f, r, 1.0f, vec3(1.0f));
        for (double th : views) {
            const Albedo a = albedo(m, viewAt(th), 50000, seed++, nonFinite);
            lo = std::min(lo, a.mean);
            hi = std::max(hi, a.mean);
            EXPECT_NEAR(a.mean, 1.0, 5.0 * a.se + 3e-3) << "roughness " << r << " view " << th << ": albedo " << a.mean << " +- " << a.se;
        }
    }
    std::printf("    white dielectric: albedo between %.5f and %.5f\n", lo, hi);
    EXPECT_EQ(nonFinite, 0);
}

// metallic 0, specularFactor 0: the Lambertian base exactly, albedo = base colour at every angle
// (every weight is (base/pi) cos / (cos/pi), so the test allows only float rounding, 1e-5).
TEST(MicrofacetFurnace, NoSpecularIsLambertian) {
    const gpu::GltfBrdf m = gpu::makeGltfBrdf(vec3(0.2f, 0.5f, 0.9f), 0.0f, 1.0f, 0.0f, vec3(1.0f));
    UniformSource rng(851);
    for (int i = 0; i < 2000; ++i) {
        const vec3 v = gpu::sampleCosineHemisphere(rng.next2()), l = gpu::sampleUniformHemisphere(rng.next2());
        const vec3 f = gpu::evalGltfBrdf(m, v, l);
        EXPECT_NEAR(f.x, 0.2 / kPi, 1e-7);
        EXPECT_NEAR(f.z, 0.9 / kPi, 1e-7);
        EXPECT_EQ(gpu::gltfSpecularProbability(m, v), 0.0f);
        EXPECT_NEAR(gpu::pdfGltfBrdf(m, v, l), l.z / kPi, 1e-6);
    }
    int nonFinite = 0;
    const Albedo a = albedo(gpu::makeGltfBrdf(vec3(1.0f), 0.0f, 1.0f, 0.0f, vec3(1.0f)), viewAt(70.0), 10000, 852, nonFinite);
    EXPECT_NEAR(a.mean, 1.0, 1e-5);
    EXPECT_EQ(nonFinite, 0);
}

// The GGX D integrates to 1 against cos(theta_h) (projected microfacet area = 1), midpoint rule in
// (theta, phi) on a grid fine enough for the narrowest lobe tested (alpha = 0.01).
TEST(MicrofacetFurnace, GgxNormalDistributionIsNormalised) {
    for (float alpha : {0.01f, 0.1f, 0.5f, 1.0f}) {
        const int nt = 20000;
        double sum = 0.0;
        for (int i = 0; i < nt; ++i) {
            const double t = (i + 0.5) * (0.5 * kPi / nt);
            const vec3 h(float(std::sin(t)), 0.0f, float(std::cos(t)));  // D is isotropic: phi integrates to 2 pi
            sum += double(gpu::ggxD(h, alpha)) * std::cos(t) * std::sin(t) * (0.5 * kPi / nt) * 2.0 * kPi;
        }
        EXPECT_NEAR(sum, 1.0, 1e-3) << "alpha " << alpha;
    }
}

// Non-negative everywhere; the specular part alone (specularFactor 1, black base, or metallic 1)
// is reciprocal (the base's weight 1 - F(n.v) is not, see microfacet.h).
TEST(MicrofacetFurnace, NonNegativeAndSpecularReciprocal) {
    UniformSource rng(861);
    for (int i = 0; i < 20000; ++i) {
        const gpu::GltfBrdf m = gpu::makeGltfBrdf(rng.next3(), rng.next(), rng.next(), rng.next(), 2.0f * rng.next3());
        const gpu::GltfBrdf metal = gpu::makeGltfBrdf(rng.next3(), 1.0f, rng.next(), 1.0f, vec3(1.0f));
        const gpu::GltfBrdf black = gpu::makeGltfBrdf(vec3(0.0f), 0.0f, rng.next(), rng.next(), 2.0f * rng.next3());
        const vec3 v = gpu::sampleUniformHemisphere(rng.next2()), l = gpu::sampleUniformHemisphere(rng.next2());
        const vec3 a = gpu::evalGltfBrdf(m, v, l);
        for (int c = 0; c < 3; ++c) ASSERT_GE(a[c], 0.0f);
        for (const gpu::GltfBrdf& s : {m, metal, black}) {  // the base's weight is reciprocal too
            const vec3 x = gpu::evalGltfBrdf(s, v, l), y = gpu::evalGltfBrdf(s, l, v);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(x[c], y[c], 1e-5f * std::max(1.0f, x[c]));
        }
    }
}

// Every function on a grid of directions that includes the pole, the horizon (z = 0, +-1e-7) and
// the lower hemisphere, for roughness 0, 1e-3 (below the clamp), 0.5 and 1: finite, non-negative.
TEST(MicrofacetFurnace, NoNaNAnywhere) {
    std::vector<vec3> dirs;
    for (float z : {1.0f, 0.999999f, 0.7f, 0.1f, 1e-4f, 1e-7f, 0.0f, -1e-7f, -0.3f, -1.0f})
        for (float phi : {0.0f, 1.0f, 2.5f, 4.0f}) {
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            dirs.push_back(vec3(r * std::cos(phi), r * std::sin(phi), z));
        }
    const vec2 us[] = {vec2(0.0f), vec2(0.5f, 0.25f), vec2(0x1.fffffep-1f, 0.0f), vec2(0x1.fffffep-1f), vec2(1e-7f, 0.9f)};
    int checked = 0;
    for (float r : {0.0f, 1e-3f, 0.5f, 1.0f})
        for (float metallic : {0.0f, 0.5f, 1.0f}) {
            const gpu::GltfBrdf m = gpu::makeGltfBrdf(vec3(1.0f, 0.5f, 0.0f), metallic, r, 1.0f, vec3(1.0f));
            for (const vec3& v : dirs) {
                for (const vec3& l : dirs) {
                    const vec3 f = gpu::evalGltfBrdf(m, v, l);
                    const float p = gpu::pdfGltfBrdf(m, v, l), pv = gpu::pdfGgxVndf(v, l, m.alpha);
                    for (float x : {f.x, f.y, f.z, p, pv}) {
                        ASSERT_TRUE(std::isfinite(x) && x >= 0.0f) << "r " << r << " v.z " << v.z << " l.z " << l.z;
                        ++checked;
                    }
                }
                for (const vec2& u : us)
                    for (float lobe : {0.0f, 0.99f}) {
                        float pdf = 0.0f;
                        const vec3 l = gpu::sampleGltfBrdf(m, v, vec3(lobe, u.x, u.y), pdf);
                        ASSERT_TRUE(std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(pdf))
                            << "r " << r << " v.z " << v.z;
                        ASSERT_GE(pdf, 0.0f);
                        const vec3 f = gpu::evalGltfBrdf(m, v, l);
                        if (pdf > 0.0f) ASSERT_TRUE(std::isfinite(f.x * l.z / pdf));
                    }
            }
        }
    EXPECT_GT(checked, 10000);
}

}  // namespace
