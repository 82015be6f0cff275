// Statistical and numerical tests of shaders/shared/sampling.h and onb.h (compiled as C++).
// For every warp: (a) chi-square goodness of fit of its samples against its pdf, (b) the pdf
// integrates to 1 over its domain, (d) sample -> invert round trip. ((c), "the pdf returned with a
// sample equals the pdf evaluated alone", concerns routines that return a pdf with the sample:
// lights and the lambertian lobe; see test_light_stats.cpp, test_scatter_stats.cpp.)
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "shared/onb.h"
#include "shared/sampling.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;

constexpr int kSamples = 200000;
constexpr double kPi = 3.14159265358979323846;

std::vector<glm::dvec3> sampleDirections(std::uint32_t seed, int n,
                                         const std::function<glm::vec3(glm::vec2)>& warp) {
    UniformSource rng(seed);
    std::vector<glm::dvec3> out;
    out.reserve(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) out.emplace_back(warp(rng.next2()));
    return out;
}

/// Distance between two values of a periodic unit coordinate (the azimuth u.y).
double circularDistance(double a, double b) {
    double d = std::fabs(a - b);
    return std::min(d, 1.0 - d);
}

/// Max round-trip error of u -> warp -> invert over n uniform u (u.y periodic).
double roundTripError(std::uint32_t seed, int n, const std::function<glm::vec2(glm::vec2)>& trip) {
    UniformSource rng(seed);
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::vec2 u = rng.next2();
        glm::vec2 v = trip(u);
        worst = std::max({worst, std::fabs(double(v.x) - u.x), circularDistance(v.y, u.y)});
    }
    return worst;
}

glm::vec3 toFloat(const glm::dvec3& d) { return glm::vec3(d); }

// ---- Orthonormal basis -----------------------------------------------------------------------

TEST(OnbTest, OrthonormalRightHandedAndInvertible) {
    UniformSource rng(11);
    std::vector<glm::vec3> normals = {
        {0, 0, 1},
        {0, 0, -1},
        {1, 0, 0},
        {0, 1, 0},
        {-1, 0, 0},
        glm::normalize(glm::vec3(0, 1e-7f, -1)),
        glm::normalize(glm::vec3(1e-7f, 0, 1)),
        glm::vec3(std::sqrt(0.5f), std::sqrt(0.5f), -0.0f)};  // n.z = -0: sign taken as +
    for (int i = 0; i < 20000; ++i) normals.push_back(gpu::sampleUniformSphere(rng.next2()));
    for (const glm::vec3& n : normals) {
        gpu::Onb f = gpu::onbFromNormal(n);
        EXPECT_NEAR(glm::length(f.s), 1.0f, 2e-6f);
        EXPECT_NEAR(glm::length(f.t), 1.0f, 2e-6f);
        EXPECT_NEAR(glm::dot(f.s, f.t), 0.0f, 2e-6f);
        EXPECT_NEAR(glm::dot(f.s, f.n), 0.0f, 2e-6f);
        EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 2e-6f);
        glm::vec3 c = glm::cross(f.s, f.t);
        ASSERT_LT(glm::length(c - n), 4e-6f) << n.x << " " << n.y << " " << n.z;
        glm::vec3 v(0.3f, -0.8f, 0.52f);
        EXPECT_LT(glm::length(gpu::toLocal(f, gpu::toWorld(f, v)) - v), 4e-6f);
        EXPECT_LT(glm::length(gpu::toWorld(f, glm::vec3(0, 0, 1)) - n), 1e-7f);
    }
}

// ---- The chi-square machinery has teeth ------------------------------------------------------

// Cosine-distributed samples tested against the uniform hemisphere pdf must be rejected
// emphatically: if this passed, the chi-square tests could not tell distributions apart.
TEST(WarpStats, TeethCosineSamplesAreNotUniform) {
    auto dirs =
        sampleDirections(7, kSamples, [](glm::vec2 u) { return gpu::sampleCosineHemisphere(u); });
    SphereBinning b;
    b.zMin = 0.0;
    b.nZ = 20;
    b.nPhi = 40;
    Chi2Result r = chi2TestDirections(
        dirs, b, [](const glm::dvec3& d) { return double(gpu::pdfUniformHemisphere(float(d.z))); });
    EXPECT_LT(r.pValue, 1e-6) << r.message;
}

// ---- Hemisphere / sphere warps ---------------------------------------------------------------

struct DirWarpCase {
    const char* name;
    std::function<glm::vec3(glm::vec2)> sample;
    std::function<double(const glm::dvec3&)> pdf;
    std::function<glm::vec2(glm::vec3)> invert;
    SphereBinning binning;
    /// Quadrature tolerance of (b): Simpson converges slowly across a jump of the pdf (a cone's
    /// rim), so pdfs with jumps are checked to 1e-3, smooth ones to 1e-4.
    double integralTol;
};

SphereBinning capBinning(double zMin, int nZ, int nPhi) {
    SphereBinning b;
    b.zMin = zMin;
    b.nZ = nZ;
    b.nPhi = nPhi;
    return b;
}

void checkDirectionWarp(const DirWarpCase& c, std::uint32_t seed) {
    SCOPED_TRACE(c.name);
    auto dirs = sampleDirections(seed, kSamples, c.sample);
    for (const glm::dvec3& d : dirs) ASSERT_NEAR(glm::length(d), 1.0, 1e-6);
    std::vector<double> cells = integrateDirectionCells(c.binning, c.pdf);
    // (b) the pdf integrates to 1 over the sphere (the cells cover it)
    double total = 0.0;
    for (double p : cells) total += p;
    EXPECT_NEAR(total, 1.0, c.integralTol);
    // (a) goodness of fit
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, c.binning, cells)));
    // (d) round trip
    double err =
        roundTripError(seed + 1, 100000, [&](glm::vec2 u) { return c.invert(c.sample(u)); });
    EXPECT_LT(err, 2e-5);
}

TEST(WarpStats, CosineHemisphere) {
    checkDirectionWarp(
        {"cosine hemisphere", [](glm::vec2 u) { return gpu::sampleCosineHemisphere(u); },
         [](const glm::dvec3& d) { return double(gpu::pdfCosineHemisphere(float(d.z))); },
         [](glm::vec3 w) { return gpu::invertCosineHemisphere(w); }, capBinning(0.0, 20, 40), 1e-4},
        101);
}

TEST(WarpStats, UniformSphere) {
    checkDirectionWarp(
        {"uniform sphere", [](glm::vec2 u) { return gpu::sampleUniformSphere(u); },
         [](const glm::dvec3&) { return double(gpu::pdfUniformSphere()); },
         [](glm::vec3 w) { return gpu::invertUniformSphere(w); }, capBinning(-1.0, 30, 40), 1e-4},
        102);
}

TEST(WarpStats, UniformHemisphere) {
    checkDirectionWarp(
        {"uniform hemisphere", [](glm::vec2 u) { return gpu::sampleUniformHemisphere(u); },
         [](const glm::dvec3& d) { return double(gpu::pdfUniformHemisphere(float(d.z))); },
         [](glm::vec3 w) { return gpu::invertUniformHemisphere(w); }, capBinning(0.0, 20, 40),
         1e-4},
        103);
}

TEST(WarpStats, UniformCones) {
    struct Cone {
        double thetaMax;  // radians
        std::uint32_t seed;
    };
    for (Cone cone : {Cone{kPi / 3, 104}, Cone{5.0 * kPi / 180, 105}, Cone{2.0 * kPi / 3, 106}}) {
        double st = std::sin(cone.thetaMax);
        float om = cone.thetaMax <= kPi / 2 ? gpu::coneOneMinusCos(float(st * st))
                                            : float(1.0 - std::cos(cone.thetaMax));
        double zMin = std::cos(std::min(kPi, cone.thetaMax * 1.1));
        checkDirectionWarp(
            {"uniform cone", [om](glm::vec2 u) { return gpu::sampleUniformCone(u, om); },
             [om](const glm::dvec3& d) { return double(gpu::pdfUniformCone(toFloat(d), om)); },
             [om](glm::vec3 w) { return gpu::invertUniformCone(w, om); }, capBinning(zMin, 12, 40),
             1e-3},
            cone.seed);
    }
}

// Small-angle accuracy: for a cone of half-angle ~1.4e-5 rad (1 - cos = 1e-10, far below float
// resolution of cos near 1), the samples must still have exactly the intended sin^2(theta), lie in
// the cone according to pdfUniformCone, and invert precisely.
TEST(WarpStats, UniformConeTinyAngleIsAccurate) {
    for (float s2 : {1e-20f, 1e-12f, 1e-8f, 1e-4f, 0.25f, 0.999f, 1.0f}) {
        double ref = s2 / (1.0 + std::sqrt(1.0 - double(s2)));
        EXPECT_NEAR(gpu::coneOneMinusCos(s2) / ref, 1.0, 1e-6) << s2;
    }
    const float om = 1e-10f;
    UniformSource rng(107);
    for (int i = 0; i < 20000; ++i) {
        glm::vec2 u = rng.next2();
        glm::vec3 w = gpu::sampleUniformCone(u, om);
        double t = double(u.x) * om;
        double sin2 = double(w.x) * w.x + double(w.y) * w.y;
        if (u.x > 1e-3f) {
            ASSERT_NEAR(sin2 / (t * (2.0 - t)), 1.0, 1e-5);
        }
        ASSERT_GT(gpu::pdfUniformCone(w, om), 0.0f);
        ASSERT_LT(std::fabs(gpu::invertUniformCone(w, om).x - u.x), 1e-5);
    }
}

// ---- Disk and ball ---------------------------------------------------------------------------

// Disk samples are tested in (r^2, phi), where the uniform disk density 1/pi per unit area
// becomes (1/pi) * (1/2), constant: dA = r dr dphi = (1/2) d(r^2) dphi.
TEST(WarpStats, UniformDisk) {
    UniformSource rng(108);
    std::vector<glm::dvec2> pts;
    for (int i = 0; i < kSamples; ++i) {
        glm::vec2 p = gpu::sampleUniformDisk(rng.next2());
        double phi = std::atan2(double(p.y), double(p.x));
        if (phi < 0.0) phi += 2.0 * kPi;
        pts.emplace_back(double(p.x) * p.x + double(p.y) * p.y, phi);
    }
    Grid2D g{0.0, 1.0, 0.0, 2.0 * kPi, 20, 40};
    auto pdf = [](double r2, double phi) {
        double r = std::sqrt(r2);
        return 0.5 * double(gpu::pdfUniformDisk(
                         glm::vec2(float(r * std::cos(phi)), float(r * std::sin(phi)))));
    };
    double total = 0.0;
    for (double p : integrateCells(g, pdf)) total += p;
    EXPECT_NEAR(total, 1.0, 1e-4);
    EXPECT_TRUE(passesChi2(chi2Test2D(pts, g, pdf)));
    // Round trip: both coordinates of the concentric map are non-periodic.
    UniformSource rt(109);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        glm::vec2 u = rt.next2();
        glm::vec2 v = gpu::invertUniformDisk(gpu::sampleUniformDisk(u));
        worst = std::max({worst, std::fabs(double(v.x) - u.x), std::fabs(double(v.y) - u.y)});
    }
    EXPECT_LT(worst, 2e-5);
}

TEST(WarpStats, UniformBall) {
    UniformSource rng(110);
    std::vector<glm::dvec3> dirs;
    std::vector<glm::dvec2> radii;  // (r, unused 0.5)
    for (int i = 0; i < kSamples; ++i) {
        glm::vec3 p = gpu::sampleUniformBall(rng.next3());
        double r = glm::length(glm::dvec3(p));
        ASSERT_LE(r, 1.0 + 1e-6);
        ASSERT_GT(gpu::pdfUniformBall(p), 0.0f);
        dirs.push_back(glm::dvec3(p) / r);
        radii.emplace_back(r, 0.5);
    }
    // Direction uniform on the sphere, radius with density 3 r^2 (volume 4/3 pi r^3 normalised),
    // which is the ball's density 3/(4 pi) integrated over the sphere of radius r: 4 pi r^2 3/(4
    // pi).
    SphereBinning b = capBinning(-1.0, 20, 40);
    EXPECT_TRUE(passesChi2(
        chi2TestDirections(dirs, b, [](const glm::dvec3&) { return 1.0 / (4.0 * kPi); })));
    Grid2D g{0.0, 1.0, 0.0, 1.0, 100, 1};
    auto radial = [](double r, double) {
        return 4.0 * kPi * r * r * double(gpu::pdfUniformBall(glm::vec3(float(r), 0.0f, 0.0f)));
    };
    double total = 0.0;
    for (double p : integrateCells(g, radial)) total += p;
    EXPECT_NEAR(total, 1.0, 1e-4);
    EXPECT_TRUE(passesChi2(chi2Test2D(radii, g, radial)));
    UniformSource rt(111);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        glm::vec3 u = rt.next3();
        if (u.z < 1e-6f) continue;  // the direction of a point at the centre is undefined
        glm::vec3 v = gpu::invertUniformBall(gpu::sampleUniformBall(u));
        worst = std::max({worst, std::fabs(double(v.x) - u.x), circularDistance(v.y, u.y),
                          std::fabs(double(v.z) - u.z)});
    }
    EXPECT_LT(worst, 2e-5);
}

}  // namespace
