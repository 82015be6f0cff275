// Statistical and numerical tests of shaders/shared/scatter.h (compiled as C++).
//  - lambertian: chi-square of sampled directions against pdfLambertian around a tilted normal,
//    the pdf integrates to 1, equals cos/pi computed independently, round trip through invert;
//  - metal: fuzz = 0 gives exact mirror directions; with fuzz the directions follow the
//    analytic density of normalize(r + fuzz * uniform ball) and the absorbed fraction equals the
//    volume of the ball cap below the surface;
//  - dielectric: the reflected fraction equals the Fresnel reflectance (exact and Schlick),
//    refraction obeys Snell's law, total internal reflection always reflects, and the Fresnel
//    functions match known values.
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shared/scatter.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::dvec3;
using glm::vec2;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;

// ---- Lambertian
// ----------------------------------------------------------------------------------

TEST(ScatterStats, Lambertian) {
    const vec3 n = glm::normalize(vec3(1.0f, 2.0f, -3.0f));
    UniformSource rng(301);
    std::vector<dvec3> dirs;
    double worstPdf = 0.0, worstTrip = 0.0;
    for (int i = 0; i < 200000; ++i) {
        vec2 u = rng.next2();
        vec3 d = gpu::sampleLambertian(n, u);
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-6f);
        double cosT = glm::dot(dvec3(n), dvec3(d));
        ASSERT_GT(cosT, 0.0);
        worstPdf = std::max(worstPdf, std::fabs(gpu::pdfLambertian(n, d) - cosT / kPi));
        vec2 back = gpu::invertLambertian(n, d);
        double ey = std::fabs(double(back.y) - u.y);
        worstTrip = std::max({worstTrip, std::fabs(double(back.x) - u.x), std::min(ey, 1.0 - ey)});
        dirs.push_back(dvec3(d));
    }
    EXPECT_LT(worstPdf, 1e-6);   // (c) the density is cos/pi
    EXPECT_LT(worstTrip, 2e-5);  // (d)
    SphereBinning b = SphereBinning::around(dvec3(n), 0.0, 20, 40);
    PdfDir pdf = [&n](const dvec3& d) { return double(gpu::pdfLambertian(n, vec3(d))); };
    std::vector<double> cells = integrateDirectionCells(b, pdf);
    double total = 0.0;
    for (double p : cells) total += p;
    EXPECT_NEAR(total, 1.0, 1e-4);                                // (b)
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));  // (a)
    // The BRDF: albedo/pi above the surface, 0 below.
    vec3 f = gpu::evalLambertian(vec3(0.5f, 0.25f, 1.0f), n, n);
    EXPECT_NEAR(f.x, 0.5f / kPi, 1e-7);
    EXPECT_NEAR(f.z, 1.0f / kPi, 1e-7);
    EXPECT_EQ(gpu::evalLambertian(vec3(1.0f), n, -n), vec3(0.0f));
    EXPECT_EQ(gpu::pdfLambertian(n, -n), 0.0f);
}

// ---- Metal
// ---------------------------------------------------------------------------------------

TEST(ScatterStats, MetalWithoutFuzzIsAMirror) {
    UniformSource rng(302);
    for (int i = 0; i < 20000; ++i) {
        vec3 n = gpu::sampleUniformSphere(rng.next2());
        vec3 d = gpu::sampleUniformSphere(rng.next2());
        if (glm::dot(d, n) > 0.0f) d = -d;
        if (glm::dot(d, n) > -1e-3f) continue;  // grazing: reflection lies on the surface
        vec3 scaled = 3.5f * d;                 // dIn need not be unit length
        bool absorbed = true;
        vec3 r = gpu::scatterMetal(scaled, n, 0.0f, rng.next3(), absorbed);
        ASSERT_FALSE(absorbed);
        dvec3 expect = dvec3(d) - 2.0 * glm::dot(dvec3(d), dvec3(n)) * dvec3(n);
        ASSERT_LT(glm::length(dvec3(r) - expect), 2e-6);
        // angle of incidence == angle of reflection, in the plane of d and n
        ASSERT_NEAR(glm::dot(r, n), -glm::dot(d, n), 2e-6f);
        ASSERT_NEAR(glm::dot(glm::cross(d, n), r), 0.0f, 2e-6f);
    }
}

/// Solid-angle density of the direction of r + f b, b uniform in the unit ball, |r| = 1 > f:
/// the ray from the origin along w crosses the ball of radius f around r between t1 and t2, and
/// P(dw) = integral of (3 / (4 pi f^3)) t^2 dt = (t2^3 - t1^3) / (4 pi f^3).
double fuzzDensity(const dvec3& w, const dvec3& r, double f) {
    double b = glm::dot(w, r);
    double disc = b * b - (1.0 - f * f);
    if (b <= 0.0 || disc <= 0.0) return 0.0;
    double s = std::sqrt(disc);
    double t1 = b - s, t2 = b + s;
    return (t2 * t2 * t2 - t1 * t1 * t1) / (4.0 * kPi * f * f * f);
}

TEST(ScatterStats, MetalFuzzFollowsBallDensity) {
    // Incidence 30 degrees off the normal: r . n = cos 30 > fuzz, so nothing is absorbed and the
    // output is exactly normalize(r + fuzz * ball).
    const float fuzz = 0.5f;
    const vec3 n(0.0f, 0.0f, 1.0f);
    const vec3 d = glm::normalize(vec3(std::sin(kPi / 6), 0.0, -std::cos(kPi / 6)));
    const dvec3 r = glm::reflect(dvec3(d), dvec3(n));
    UniformSource rng(303);
    std::vector<dvec3> dirs;
    for (int i = 0; i < 200000; ++i) {
        bool absorbed = true;
        vec3 o = gpu::scatterMetal(d, n, fuzz, rng.next3(), absorbed);
        ASSERT_FALSE(absorbed);
        ASSERT_NEAR(glm::length(o), 1.0f, 1e-6f);
        dirs.push_back(dvec3(o));
    }
    double zMin = std::cos(std::asin(double(fuzz)) * 1.05);
    SphereBinning b = SphereBinning::around(r, zMin, 20, 40);
    PdfDir pdf = [&](const dvec3& w) { return fuzzDensity(w, r, fuzz); };
    std::vector<double> cells = integrateDirectionCells(b, pdf);
    double total = 0.0;
    for (double p : cells) total += p;
    ASSERT_NEAR(total, 1.0, 1e-3);  // checks the reference density itself
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, b, cells)));
}

TEST(ScatterStats, MetalAbsorbedFractionIsTheBallCapBelowTheSurface) {
    // r . n = h < fuzz: absorbed iff b . n <= -h / fuzz = -c, a cap of the unit ball of volume
    // fraction (1 - c)^2 (2 + c) / 4.
    const float fuzz = 0.8f;
    const vec3 n = glm::normalize(vec3(0.3f, -0.2f, 1.0f));
    gpu::Onb f = gpu::onbFromNormal(n);
    const vec3 d = gpu::toWorld(f, glm::normalize(vec3(0.9f, 0.1f, -0.3f)));
    const double h = glm::dot(glm::reflect(dvec3(d), dvec3(n)), dvec3(n));
    const double c = h / fuzz;
    const double pAbsorbed = (1.0 - c) * (1.0 - c) * (2.0 + c) / 4.0;
    UniformSource rng(304);
    const int n0 = 200000;
    double absorbedCount = 0.0;
    for (int i = 0; i < n0; ++i) {
        bool absorbed = false;
        vec3 o = gpu::scatterMetal(d, n, fuzz, rng.next3(), absorbed);
        if (absorbed) {
            absorbedCount += 1.0;
        } else {
            ASSERT_GT(glm::dot(o, n), 0.0f);
            ASSERT_NEAR(glm::length(o), 1.0f, 1e-6f);
        }
    }
    Chi2Result r =
        chi2Test({absorbedCount, n0 - absorbedCount}, {n0 * pAbsorbed, n0 * (1.0 - pAbsorbed)});
    r.message += " (absorbed " + std::to_string(absorbedCount / n0) + ", expected " +
                 std::to_string(pAbsorbed) + ")";
    EXPECT_TRUE(passesChi2(r));
}

// ---- Fresnel
// -------------------------------------------------------------------------------------

TEST(ScatterStats, FresnelKnownValues) {
    const float ior = 1.5f;
    const float r0 = 0.04f;  // ((1 - 1.5) / (1 + 1.5))^2
    EXPECT_NEAR(gpu::fresnelDielectricExact(1.0f, ior), r0, 1e-6f);
    EXPECT_NEAR(gpu::fresnelDielectricExact(1.0f, 1.0f / ior), r0, 1e-6f);
    EXPECT_NEAR(gpu::fresnelSchlick(1.0f, ior), r0, 1e-6f);
    EXPECT_NEAR(gpu::fresnelSchlick(1.0f, 1.0f / ior), r0, 1e-6f);
    EXPECT_NEAR(gpu::fresnelSchlick(0.0f, ior), 1.0f, 1e-6f);
    EXPECT_NEAR(gpu::fresnelDielectricExact(0.0f, ior), 1.0f, 1e-6f);
    // Brewster's angle tan(theta_B) = eta: the parallel part vanishes, F = r_perp^2 / 2 with
    // r_perp = (cos i - eta cos t) / (cos i + eta cos t) and theta_i + theta_t = 90 degrees.
    double thetaB = std::atan(1.5);
    double ci = std::cos(thetaB), ct = std::sin(thetaB);
    double rPerp = (ci - 1.5 * ct) / (ci + 1.5 * ct);
    EXPECT_NEAR(gpu::fresnelDielectricExact(float(ci), ior), 0.5 * rPerp * rPerp, 1e-6);
    // Total internal reflection from inside beyond the critical angle asin(1/1.5).
    double crit = std::asin(1.0 / 1.5);
    EXPECT_EQ(gpu::fresnelDielectricExact(float(std::cos(crit + 0.01)), 1.0f / ior), 1.0f);
    EXPECT_LT(gpu::fresnelDielectricExact(float(std::cos(crit - 0.01)), 1.0f / ior), 1.0f);
    EXPECT_EQ(gpu::dielectricReflectProbability(float(std::cos(crit + 0.01)), ior, false), 1.0f);
    // Reciprocity: F(theta_i, eta) == F(theta_t, 1/eta); a negative cosine means "from the other
    // side"; F in [0,1]; Schlick within 0.05 of exact when entering glass (a known bound).
    for (int i = 0; i <= 100; ++i) {
        double cosI = i / 100.0;
        double sinT = std::sqrt(1.0 - cosI * cosI) / 1.5;
        double cosT = std::sqrt(1.0 - sinT * sinT);
        float fi = gpu::fresnelDielectricExact(float(cosI), ior);
        // (from inside near the critical angle cos t = sqrt(1 - sin^2 t) is ill-conditioned in
        // float, hence 1e-4)
        EXPECT_NEAR(fi, gpu::fresnelDielectricExact(float(cosT), 1.0f / ior), 1e-4f) << cosI;
        EXPECT_EQ(fi, gpu::fresnelDielectricExact(-float(cosI), 1.0f / ior));
        EXPECT_TRUE(fi >= 0.0f && fi <= 1.0f);
        EXPECT_NEAR(gpu::fresnelSchlick(float(cosI), ior), fi, 0.05f) << cosI;
    }
}

// ---- Dielectric
// ----------------------------------------------------------------------------------

struct DielectricCase {
    double thetaDeg;  // angle of incidence
    bool frontFace;
    bool exact;
};

TEST(ScatterStats, DielectricReflectsWithFresnelProbabilityAndRefractsBySnell) {
    const float ior = 1.5f;
    const vec3 n = glm::normalize(vec3(-0.2f, 1.0f, 0.4f));  // faces the incoming ray
    gpu::Onb frame = gpu::onbFromNormal(n);
    std::uint32_t seed = 305;
    for (DielectricCase c : {DielectricCase{10, true, true}, DielectricCase{60, true, true},
                             DielectricCase{85, true, false}, DielectricCase{30, false, true},
                             DielectricCase{40, false, false}, DielectricCase{41.5, false, true}}) {
        SCOPED_TRACE(testing::Message()
                     << c.thetaDeg << " deg, front " << c.frontFace << ", exact " << c.exact);
        double th = c.thetaDeg * kPi / 180.0;
        vec3 d = gpu::toWorld(frame, vec3(float(std::sin(th)), 0.0f, -float(std::cos(th))));
        double cosI = -glm::dot(dvec3(d), dvec3(n));
        double eta = c.frontFace ? 1.0 / ior : ior;  // eta_i / eta_t
        double sinT = eta * std::sqrt(std::max(0.0, 1.0 - cosI * cosI));
        ASSERT_LT(sinT, 1.0);  // these cases all refract sometimes
        double F = c.exact ? gpu::fresnelDielectricExact(float(cosI), float(1.0 / eta))
                           : gpu::fresnelSchlick(float(cosI), float(eta));
        UniformSource rng(seed++);
        const int count = 100000;
        double reflected = 0.0;
        for (int i = 0; i < count; ++i) {
            vec3 o = gpu::scatterDielectric(d, n, c.frontFace, ior, c.exact, rng.next());
            ASSERT_NEAR(glm::length(o), 1.0f, 1e-6f);
            if (glm::dot(o, n) > 0.0f) {
                reflected += 1.0;
                ASSERT_LT(glm::length(o - glm::reflect(d, n)), 1e-6f);
            } else {
                // Snell: sin(theta_t) = eta sin(theta_i), in the plane of incidence.
                double sinO = glm::length(glm::cross(dvec3(o), dvec3(n)));
                ASSERT_NEAR(sinO, sinT, 2e-6);
                ASSERT_NEAR(glm::dot(glm::cross(d, n), o), 0.0f, 2e-6f);
                ASSERT_GT(glm::dot(o, d), 0.0f);  // onward, not back
            }
        }
        Chi2Result r = chi2Test({reflected, count - reflected}, {count * F, count * (1.0 - F)});
        r.message += " (reflected " + std::to_string(reflected / count) + ", Fresnel " +
                     std::to_string(F) + ")";
        EXPECT_TRUE(passesChi2(r));
    }
}

TEST(ScatterStats, DielectricTotalInternalReflectionAlwaysReflects) {
    const vec3 n(0.0f, 0.0f, 1.0f);
    for (double deg : {42.5, 60.0, 89.0}) {
        double th = deg * kPi / 180.0;
        vec3 d(float(std::sin(th)), 0.0f, -float(std::cos(th)));
        for (float u : {0.0f, 0.5f, 0.999999f}) {
            for (bool exact : {false, true}) {
                vec3 o = gpu::scatterDielectric(d, n, false, 1.5f, exact, u);
                EXPECT_LT(glm::length(o - glm::reflect(d, n)), 1e-6f) << deg;
            }
        }
    }
}

}  // namespace
