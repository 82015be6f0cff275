// Statistical and numerical tests of shaders/shared/light_sampling.h (compiled as C++).
// For every light kind and several configurations (near, far, grazing, and for spheres the cone,
// on-surface and inside strategies): (a) chi-square goodness of fit of the sampled directions
// against pdfXLight, (b) pdfXLight integrates to 1 over the sphere of directions, (c) the pdf
// returned with each sample equals pdfXLight(dir) evaluated alone, (d) invertXLight round trip.
// Directions are binned in a frame chosen per light, over a cap or (z, phi) box that contains it
// (plus cells for the rest of the sphere), so the cells resolve the light however it looks.
// Significance: each chi-square test runs at statsAlpha() (stat_suite.h: Sidak-corrected so the
// whole stats suite falsely fails with probability <= 1% for correct code; seeds are fixed).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "shared/light_sampling.h"
#include "shared/rect_sampling.h"
#include "shared/triangle_sampling.h"
#include "stat_suite.h"

namespace {

using namespace vkp::test;
namespace gpu = vkp::gpu;
using glm::vec2;
using glm::vec3;

constexpr int kSamples = 100000;
constexpr double kPi = 3.14159265358979323846;

/// One light seen from one point, as closures over the shared functions.
struct LightCase {
    std::string name;
    std::function<gpu::LightSample(vec2)> sample;
    std::function<float(vec3)> pdf;
    std::function<vec2(vec3)> invert;
    SphereBinning binning;
    bool periodicY = false;  ///< xi.y is an azimuth (sphere strategies)
};

/// Binning for a planar light (Q + a e1 + b e2; a triangle if tri): the frame's axis is the
/// light's normal, oriented from p towards its plane, so z = cos(angle to the normal) and the
/// light's image in (z, phi) is a compact region even at grazing angles. If the axis from p hits
/// the light, its image contains the pole: a cap z >= zMin. Otherwise a (z, phi) box, with the
/// azimuth measured from the light's centroid so the box does not wrap around +-pi. The bounds
/// come from a dense grid of points on the light, widened by 5%.
SphereBinning planarBinning(vec3 p, vec3 Q, vec3 e1, vec3 e2, bool tri) {
    glm::dvec3 n = glm::normalize(glm::cross(glm::dvec3(e1), glm::dvec3(e2)));
    glm::dvec3 centroid = glm::dvec3(Q) + (tri ? 1.0 / 3.0 : 0.5) * glm::dvec3(e1 + e2);
    glm::dvec3 toLight = centroid - glm::dvec3(p);
    if (glm::dot(n, toLight) < 0.0) n = -n;
    SphereBinning b = SphereBinning::around(n, -1.0, 20, 40);
    glm::dvec3 side = toLight - glm::dot(toLight, n) * n;
    if (glm::length(side) > 1e-9 * glm::length(toLight)) {
        b.s = glm::normalize(side);
        b.t = glm::cross(n, b.s);
    }
    double zLo = 1.0, zHi = -1.0, phiLo = kPi, phiHi = -kPi;
    const int m = 64;
    for (int i = 0; i <= m; ++i) {
        for (int j = 0; j <= m; ++j) {
            double a = double(i) / m, c = double(j) / m;
            if (tri && a + c > 1.0) continue;
            glm::dvec3 x = glm::dvec3(Q) + a * glm::dvec3(e1) + c * glm::dvec3(e2);
            glm::dvec2 zp = b.zPhi(x - glm::dvec3(p));
            zLo = std::min(zLo, zp.x);
            zHi = std::max(zHi, zp.x);
            phiLo = std::min(phiLo, zp.y);
            phiHi = std::max(phiHi, zp.y);
        }
    }
    vec2 ab;
    bool poleInside = gpu::intersectParallelogram(Q, e1, e2, tri, p, vec3(n), 0.0f, gpu::VKP_FAR,
                                                  ab) < gpu::VKP_FAR;
    double dz = 0.05 * (zHi - zLo);
    if (poleInside) return SphereBinning::around(n, std::max(-1.0, zLo - dz), 20, 40);
    double dphi = 0.05 * (phiHi - phiLo);
    b.zMin = std::max(-1.0, zLo - dz);
    b.zMax = std::min(1.0, zHi + dz);
    b.phiMin = std::max(-kPi, phiLo - dphi);
    b.phiMax = std::min(kPi, phiHi + dphi);
    return b;
}

LightCase quadCase(const std::string& name, vec3 Q, vec3 u, vec3 v, vec3 p) {
    LightCase c;
    c.name = name;
    c.sample = [=](vec2 xi) { return gpu::sampleQuadLight(Q, u, v, p, xi); };
    c.pdf = [=](vec3 d) { return gpu::pdfQuadLight(Q, u, v, p, d); };
    c.invert = [=](vec3 d) { return gpu::invertQuadLight(Q, u, v, p, d); };
    c.binning = planarBinning(p, Q, u, v, false);
    return c;
}

LightCase triangleCase(const std::string& name, vec3 v0, vec3 e1, vec3 e2, vec3 p) {
    LightCase c;
    c.name = name;
    c.sample = [=](vec2 xi) { return gpu::sampleTriangleLight(v0, e1, e2, p, xi); };
    c.pdf = [=](vec3 d) { return gpu::pdfTriangleLight(v0, e1, e2, p, d); };
    c.invert = [=](vec3 d) { return gpu::invertTriangleLight(v0, e1, e2, p, d); };
    c.binning = planarBinning(p, v0, e1, e2, true);
    return c;
}

LightCase sphereCase(const std::string& name, vec3 centre, float R, vec3 p) {
    LightCase c;
    c.name = name;
    c.sample = [=](vec2 xi) { return gpu::sampleSphereLight(centre, R, p, xi); };
    c.pdf = [=](vec3 d) { return gpu::pdfSphereLight(centre, R, p, d); };
    c.invert = [=](vec3 d) { return gpu::invertSphereLight(centre, R, p, d); };
    c.periodicY = true;
    double d = glm::length(glm::dvec3(centre) - glm::dvec3(p));
    glm::dvec3 axis = d > 0.0 ? (glm::dvec3(centre) - glm::dvec3(p)) / d : glm::dvec3(0, 0, 1);
    double zMin = -1.0;
    if (d > R * 1.0001) zMin = std::cos(std::min(kPi, 1.1 * std::asin(R / d) + 1e-3));
    c.binning = SphereBinning::around(axis, zMin, 20, 40);
    return c;
}

/// Runs (a)-(d) on one configuration.
void checkLight(const LightCase& c, std::uint32_t seed, double integralTol = 5e-4) {
    SCOPED_TRACE(c.name);
    UniformSource rng(seed);
    std::vector<glm::dvec3> dirs;
    int invalid = 0, pdfMismatch = 0, pdfZeroAlone = 0, invertBad = 0;
    double worstRel = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        vec2 xi = rng.next2();
        gpu::LightSample s = c.sample(xi);
        ASSERT_TRUE(std::isfinite(s.pdf) && std::isfinite(s.dist) && std::isfinite(s.dir.x) &&
                    std::isfinite(s.dir.y) && std::isfinite(s.dir.z));
        if (s.pdf == 0.0f) {
            ++invalid;
            continue;
        }
        ASSERT_NEAR(glm::length(s.dir), 1.0f, 1e-5f);
        ASSERT_GT(s.dist, 0.0f);
        dirs.emplace_back(s.dir);
        // (c) the pdf evaluated alone
        float alone = c.pdf(s.dir);
        if (alone == 0.0f) {
            ++pdfZeroAlone;  // the ray cast missed at the light's rim (rounding)
        } else {
            double rel = std::fabs(double(alone) / s.pdf - 1.0);
            worstRel = std::max(worstRel, rel);
            if (rel > 1e-3) ++pdfMismatch;
        }
        // (d) round trip
        if (!c.invert) continue;
        vec2 back = c.invert(s.dir);
        double ex = std::fabs(double(back.x) - xi.x);
        double ey = std::fabs(double(back.y) - xi.y);
        if (c.periodicY) ey = std::min(ey, 1.0 - ey);
        if (!(std::max(ex, ey) < 1e-3)) ++invertBad;
    }
    std::printf(
        "    [%s] invalid %d, pdf alone = 0: %d, pdf mismatches %d (max rel %.2g), "
        "inverse off: %d\n",
        c.name.c_str(), invalid, pdfZeroAlone, pdfMismatch, worstRel, invertBad);
    EXPECT_LE(invalid, kSamples / 10000);
    EXPECT_LE(pdfZeroAlone, kSamples / 10000);
    EXPECT_LE(pdfMismatch, kSamples / 10000);
    EXPECT_LE(invertBad, kSamples / 1000);
    // (b) and (a)
    PdfDir pdf = [&c](const glm::dvec3& d) { return double(c.pdf(vec3(d))); };
    std::vector<double> cells = integrateDirectionCells(c.binning, pdf, 1e-4, 8, 1);
    double total = 0.0;
    for (double p : cells) total += p;
    std::printf("    [%s] integral of the pdf over the sphere: %.6f\n", c.name.c_str(), total);
    EXPECT_NEAR(total, 1.0, integralTol);
    EXPECT_TRUE(passesChi2(chi2TestDirections(dirs, c.binning, cells)));
}

// ---- Quads --------------------------------------------------------------------------------------

const vec3 kQ(-1.0f, -0.5f, 2.0f), kU(2.0f, 0.0f, 0.0f), kV(0.0f, 1.0f, 0.0f);

TEST(LightStats, QuadNear) {
    checkLight(quadCase("quad near", kQ, kU, kV, vec3(0.2f, 0.1f, 1.7f)), 201);
}
TEST(LightStats, QuadFar) {
    checkLight(quadCase("quad far", kQ, kU, kV, vec3(3.0f, -4.0f, -30.0f)), 202);
}
TEST(LightStats, QuadGrazing) {
    checkLight(quadCase("quad grazing", kQ, kU, kV, vec3(0.0f, -3.0f, 2.05f)), 203);
}
TEST(LightStats, QuadSkewedFromBehind) {
    // A sheared parallelogram seen from its back side (both faces are sampled).
    checkLight(quadCase("quad skewed", vec3(0.5f, 0.2f, -1.0f), vec3(1.5f, 0.2f, 0.6f),
                        vec3(0.9f, 1.1f, -0.2f), vec3(1.0f, 0.5f, 1.0f)),
               204);
}

// ---- Rectangles, uniform in solid angle (Urena et al. 2013; area sampling as fallback) --------

/// minSize: the apparent size (sr) below which the light is sampled in area (--light-sampling auto).
LightCase rectCase(const std::string& name, vec3 Q, vec3 u, vec3 v, vec3 p, bool expectSolidAngle, float minSize = 0.0f) {
    LightCase c;
    c.name = name;
    c.sample = [=](vec2 xi) { return gpu::sampleRectLight(Q, u, v, p, xi, minSize); };
    c.pdf = [=](vec3 d) { return gpu::pdfRectLight(Q, u, v, p, d, minSize); };
    c.binning = planarBinning(p, Q, u, v, false);
    EXPECT_EQ(gpu::rectLightUsesSolidAngle(Q, u, v, p, minSize), expectSolidAngle) << name;
    if (minSize == 0.0f)
        EXPECT_EQ(gpu::useSphericalRect(u, v, gpu::sphericalRectInit(Q, u, v, p)), expectSolidAngle) << name;
    return c;
}

TEST(LightStats, RectSolidAngleNear) {
    checkLight(rectCase("rect near", kQ, kU, kV, vec3(0.2f, 0.1f, 1.7f), true), 211);
}
TEST(LightStats, RectSolidAngleOffAxisFromBehind) {
    // Rotated rectangle (u, v not axis-aligned), seen from its back side.
    const vec3 u(1.2f, 0.0f, 0.9f), v(0.0f, 0.7f, 0.0f);
    checkLight(rectCase("rect rotated", vec3(0.0f, 0.0f, 0.0f), u, v, vec3(-0.8f, 1.5f, 1.3f), true), 212);
}
TEST(LightStats, RectSolidAngleGrazing) {
    checkLight(rectCase("rect grazing", kQ, kU, kV, vec3(0.0f, -3.0f, 2.3f), true), 213);
}
TEST(LightStats, RectTinyFallsBackToArea) {
    checkLight(rectCase("rect tiny", kQ, kU, kV, vec3(3.0f, -4.0f, -300.0f), false), 214);
}
TEST(LightStats, ParallelogramFallsBackToArea) {
    checkLight(rectCase("parallelogram", vec3(0.5f, 0.2f, -1.0f), vec3(1.5f, 0.2f, 0.6f), vec3(0.9f, 1.1f, -0.2f),
                        vec3(1.0f, 0.5f, 1.0f), false),
               215);
}

// The pdf of solid-angle sampling is the constant 1/S, S the rectangle's solid angle, which for a
// square of side 2a seen from distance h above its centre is 4 asin(a^2 / (a^2 + h^2)).
TEST(LightStats, RectSolidAngleIsExact) {
    const float a = 0.5f, h = 0.8f;
    const vec3 Q(-a, -a, 0.0f), u(2 * a, 0, 0), v(0, 2 * a, 0), p(0, 0, h);
    const double S = 4.0 * std::asin(double(a) * a / (double(a) * a + double(h) * h));
    EXPECT_NEAR(gpu::sphericalRectInit(Q, u, v, p).S, S, 1e-5 * S);
    UniformSource rng(216);
    for (int i = 0; i < 1000; ++i) {
        gpu::LightSample s = gpu::sampleRectLight(Q, u, v, p, rng.next2(), 0.0f);
        EXPECT_NEAR(s.pdf, 1.0 / S, 1e-5 / S);
    }
}

// ---- Triangles ----------------------------------------------------------------------------------

const vec3 kV0(0.0f, 0.0f, 0.0f), kE1(1.0f, 0.0f, 0.2f), kE2(0.3f, 1.2f, 0.0f);

TEST(LightStats, TriangleNear) {
    checkLight(triangleCase("triangle near", kV0, kE1, kE2, vec3(0.3f, 0.4f, 0.5f)), 205);
}
TEST(LightStats, TriangleFar) {
    checkLight(triangleCase("triangle far", kV0, kE1, kE2, vec3(-10.0f, 20.0f, 15.0f)), 206);
}
TEST(LightStats, TriangleGrazing) {
    // p 0.05 above the triangle's plane, about 1.3 away from the triangle.
    vec3 n = glm::normalize(glm::cross(kE1, kE2));
    vec3 p = kV0 - 1.2f * kE1 + 0.4f * kE2 + 0.05f * n;
    checkLight(triangleCase("triangle grazing", kV0, kE1, kE2, p), 207);
}

// ---- Triangles, uniform in solid angle (Arvo 1995; area sampling as fallback) ------------------

/// minSize: the apparent size (sr) below which the light is sampled in area (--light-sampling auto).
LightCase sphTriCase(const std::string& name, vec3 v0, vec3 e1, vec3 e2, vec3 p, bool expectSolidAngle,
                     float minSize = 0.0f) {
    LightCase c;
    c.name = name;
    c.sample = [=](vec2 xi) { return gpu::sampleTriangleLightSolidAngle(v0, e1, e2, p, xi, minSize); };
    c.pdf = [=](vec3 d) { return gpu::pdfTriangleLightSolidAngle(v0, e1, e2, p, d, minSize); };
    c.binning = planarBinning(p, v0, e1, e2, true);
    EXPECT_EQ(gpu::triangleLightUsesSolidAngle(v0, e1, e2, p, minSize), expectSolidAngle) << name;
    if (minSize == 0.0f)
        EXPECT_EQ(gpu::useSphericalTriangle(gpu::triangleLightSolidAngle(v0, e1, e2, p)), expectSolidAngle) << name;
    return c;
}

TEST(LightStats, SphericalTriangleNear) {
    checkLight(sphTriCase("spherical triangle near", kV0, kE1, kE2, vec3(0.3f, 0.4f, 0.5f), true), 221);
}
TEST(LightStats, SphericalTriangleVeryNear) {
    // 0.02 above the triangle's interior: S close to 2 pi (but below the fallback).
    vec3 n = glm::normalize(glm::cross(kE1, kE2));
    checkLight(sphTriCase("spherical triangle very near", kV0, kE1, kE2, kV0 + 0.3f * kE1 + 0.3f * kE2 + 0.02f * n, true),
               222);
}
TEST(LightStats, SphericalTriangleGrazingFromBehind) {
    vec3 n = glm::normalize(glm::cross(kE1, kE2));
    vec3 p = kV0 - 0.4f * kE1 + 0.4f * kE2 - 0.05f * n;  // 0.05 behind its plane, 0.4 beyond an edge
    checkLight(sphTriCase("spherical triangle grazing", kV0, kE1, kE2, p, true), 223);
}
TEST(LightStats, SphericalTriangleTinyFallsBackToArea) {
    checkLight(sphTriCase("spherical triangle tiny", kV0, kE1, kE2, vec3(-30.0f, 60.0f, 45.0f), false), 224);
}
// The pdf is the constant 1/S: for the octant triangle (1,0,0), (0,1,0), (0,0,1) seen from the
// origin S = pi/2 exactly, and every sampled direction has positive coordinates.
TEST(LightStats, SphericalTriangleSolidAngleIsExact) {
    const vec3 v0(1, 0, 0), e1(-1, 1, 0), e2(-1, 0, 1), p(0, 0, 0);
    EXPECT_NEAR(gpu::triangleLightSolidAngle(v0, e1, e2, p), kPi / 2, 1e-6);
    UniformSource rng(225);
    for (int i = 0; i < 10000; ++i) {
        const gpu::LightSample s = gpu::sampleTriangleLightSolidAngle(v0, e1, e2, p, rng.next2(), 0.0f);
        ASSERT_NEAR(s.pdf, 2.0 / kPi, 1e-6);
        ASSERT_GE(std::min(s.dir.x, std::min(s.dir.y, s.dir.z)), -1e-6f);
        ASSERT_NEAR(s.dir.x + s.dir.y + s.dir.z, 1.0f / s.dist, 1e-4f);  // the point lies on x + y + z = 1
    }
}

// ---- The size switch of `--light-sampling auto` ---------------------------------------------------
// Solid-angle sampling only from points where the light looks at least minSize large (area over
// squared distance to its centre); area sampling elsewhere. The same point on either side of the
// switch: each branch passes chi-square and sample/pdf consistency on its own.

TEST(LightStats, ApparentSizeIsAreaOverSquaredDistanceToTheCentre) {
    // kQ + a kU + b kV: area |kU x kV|; from 2 above its centre it looks area / 4 large.
    const vec3 c = kQ + 0.5f * (kU + kV), n = glm::normalize(glm::cross(kU, kV));
    const float area = glm::length(glm::cross(kU, kV));
    EXPECT_FLOAT_EQ(gpu::apparentSize(area, c, c + 2.0f * n), area / 4.0f);
    EXPECT_TRUE(gpu::rectLargeEnough(kQ, kU, kV, c + 2.0f * n, 0.249f * area));
    EXPECT_FALSE(gpu::rectLargeEnough(kQ, kU, kV, c + 2.0f * n, 0.251f * area));
    EXPECT_TRUE(gpu::rectLargeEnough(kQ, kU, kV, c + 2.0f * n, 0.0f));
    EXPECT_TRUE(gpu::rectLargeEnough(kQ, kU, kV, c, 1e30f));  // at the centre: as large as it gets
    // Triangle: half the parallelogram's area, centred at its centroid.
    const vec3 g = kV0 + (kE1 + kE2) / 3.0f, m = glm::normalize(glm::cross(kE1, kE2));
    const float triArea = 0.5f * glm::length(glm::cross(kE1, kE2));
    EXPECT_TRUE(gpu::triangleLargeEnough(kV0, kE1, kE2, g + 3.0f * m, 0.999f * triArea / 9.0f));
    EXPECT_FALSE(gpu::triangleLargeEnough(kV0, kE1, kE2, g + 3.0f * m, 1.001f * triArea / 9.0f));
}

TEST(LightStats, RectBelowMinSizeSamplesArea) {
    // From "rect near" the light looks 14.3 sr large (area 2 at distance^2 0.14): minSize 20
    // switches it to area sampling.
    checkLight(rectCase("rect near, switched to area", kQ, kU, kV, vec3(0.2f, 0.1f, 1.7f), false, 20.0f), 217);
}
TEST(LightStats, RectAboveMinSizeSamplesSolidAngle) {
    checkLight(rectCase("rect near, above the switch", kQ, kU, kV, vec3(0.2f, 0.1f, 1.7f), true, 10.0f), 218);
}
TEST(LightStats, SphericalTriangleBelowMinSizeSamplesArea) {
    // From "spherical triangle near" the triangle looks 2.97 sr large (area 0.612, distance^2 0.206).
    checkLight(sphTriCase("spherical triangle near, switched to area", kV0, kE1, kE2, vec3(0.3f, 0.4f, 0.5f), false, 10.0f), 227);
}
TEST(LightStats, SphericalTriangleAboveMinSizeSamplesSolidAngle) {
    checkLight(sphTriCase("spherical triangle near, above the switch", kV0, kE1, kE2, vec3(0.3f, 0.4f, 0.5f), true, 2.0f), 228);
}

// Which triangle sampler the numbers favour (issue 5: "area or spherical triangle sampling
// (Arvo), whichever the numbers favour"): the variance of the one-sample irradiance estimate
// cos_x / pdf at a point x (normal n, towards the light) under a triangle of radiance 1, for a
// light near, at mid distance and far. Solid-angle sampling removes the 1/r^2 cos_light factor
// from the weight, leaving only cos_x: its variance is 21.5x lower near, 14.1x at mid distance, and
// identical far, where it falls back to area sampling (same code path). Deterministic (fixed seed,
// 200k samples); the assertions (>= 10x, >= 5x, equal) are far from the sampling error of the
// ratios. On the device, cornell-classic with its light as two triangles (64x64, 64 spp, mis):
// relMSE 0.00498 (area) -> 0.00486 (solid angle); the ceiling light is small and far from most of
// the box, so the image gains little; a large light near surfaces gains the factors above.
TEST(LightStats, SphericalTriangleVarianceIsLowerNearTheLight) {
    const vec3 n(0.0f, 0.0f, 1.0f);
    struct Geometry {
        const char* name;
        vec3 v0, e1, e2;
        double minRatio;  ///< area variance / solid-angle variance must be at least this (0: equal)
    };
    const Geometry cases[] = {
        {"near (0.3 below a unit triangle)", vec3(-0.4f, -0.3f, 0.3f), vec3(1.0f, 0.1f, 0.0f), vec3(0.2f, 1.0f, 0.1f), 10.0},
        {"mid (3 below, off axis)", vec3(1.0f, -0.5f, 3.0f), vec3(1.0f, 0.1f, 0.0f), vec3(0.2f, 1.0f, 0.1f), 5.0},
        {"far (falls back to area)", vec3(10.0f, 5.0f, 60.0f), vec3(1.0f, 0.1f, 0.0f), vec3(0.2f, 1.0f, 0.1f), 0.0},
    };
    for (const Geometry& g : cases) {
        double m[2] = {0, 0}, q[2] = {0, 0};
        const int N = 200000;
        for (int k = 0; k < 2; ++k) {
            UniformSource rng(226);
            for (int i = 0; i < N; ++i) {
                const vec2 xi = rng.next2();
                const gpu::LightSample ls = k == 0 ? gpu::sampleTriangleLight(g.v0, g.e1, g.e2, vec3(0.0f), xi)
                                                   : gpu::sampleTriangleLightSolidAngle(g.v0, g.e1, g.e2, vec3(0.0f), xi, 0.0f);
                const double f = (ls.pdf > 0.0f) ? std::max(0.0, double(glm::dot(ls.dir, n))) / ls.pdf : 0.0;
                m[k] += f;
                q[k] += f * f;
            }
        }
        const double mean0 = m[0] / N, mean1 = m[1] / N;
        const double var0 = q[0] / N - mean0 * mean0, var1 = q[1] / N - mean1 * mean1;
        std::printf("    [%s] irradiance %.5f (area) %.5f (solid angle); variance area / solid angle = %.3f\n", g.name,
                    mean0, mean1, var0 / var1);
        EXPECT_NEAR(mean0, mean1, 4.0 * std::sqrt((var0 + var1) / N));
        if (g.minRatio > 0.0)
            EXPECT_GE(var0 / var1, g.minRatio) << g.name;
        else
            EXPECT_EQ(var0, var1) << g.name << ": the fallback should be area sampling itself";
    }
}

// ---- Spheres ------------------------------------------------------------------------------------

const vec3 kC(0.3f, -0.2f, 1.0f);

TEST(LightStats, SphereConeNear) {
    checkLight(sphereCase("sphere cone d=1.5R", kC, 1.0f, kC + vec3(0.0f, 1.5f, 0.0f)), 208);
}
TEST(LightStats, SphereConeJustOutside) {
    // d = 1.001 R: theta_max ~ 87.4 degrees; d^2 - R^2 would lose 3 digits if formed directly.
    vec3 dir = glm::normalize(vec3(1.0f, -2.0f, 0.5f));
    checkLight(sphereCase("sphere cone d=1.001R", kC, 2.0f, kC + 2.002f * dir), 209);
}
TEST(LightStats, SphereConeFar) {
    checkLight(sphereCase("sphere cone d=40R", kC, 0.5f, kC + vec3(15.0f, -10.0f, 25.0f) * 0.65f),
               210);
}
TEST(LightStats, SphereOnSurface) {
    vec3 dir = glm::normalize(vec3(1.0f, 2.0f, 3.0f));
    vec3 p = kC + 1.5f * dir;
    ASSERT_EQ(gpu::sphereLightStrategy(glm::length(kC - p), 1.5f), gpu::SPHERE_LIGHT_SURFACE);
    checkLight(sphereCase("sphere on surface", kC, 1.5f, p), 211);
}
TEST(LightStats, SphereInsideOffCentre) {
    vec3 p = kC + vec3(0.4f, -0.3f, 0.2f);
    ASSERT_EQ(gpu::sphereLightStrategy(glm::length(kC - p), 1.0f), gpu::SPHERE_LIGHT_INSIDE);
    checkLight(sphereCase("sphere inside", kC, 1.0f, p), 212);
}
TEST(LightStats, SphereInsideNearSurface) {
    vec3 p = kC + 0.999f * glm::normalize(vec3(-1.0f, 0.5f, 0.25f));
    checkLight(sphereCase("sphere inside d=0.999R", kC, 1.0f, p), 213);
}
TEST(LightStats, SphereAtCentre) { checkLight(sphereCase("sphere at centre", kC, 1.0f, kC), 214); }

// ---- Sphere light: the fallback strategies are the area densities they claim to be ------------

// On the surface and inside, the returned pdf must equal the solid-angle form of uniform area
// sampling, dist^2 / (|cos_light| 4 pi R^2), evaluated from the sample's own point and normal.
TEST(LightStats, SphereFallbacksAreUniformAreaDensities) {
    struct Where {
        float d;
        const char* name;
    };
    const float R = 1.5f;
    for (Where w : {Where{R, "on surface"}, Where{R * 0.999f, "inside near surface"},
                    Where{R * 0.5f, "inside"}, Where{0.0f, "centre"}}) {
        SCOPED_TRACE(w.name);
        vec3 p = kC + w.d * glm::normalize(vec3(0.2f, -1.0f, 0.4f));
        UniformSource rng(215);
        for (int i = 0; i < 20000; ++i) {
            gpu::LightSample s = gpu::sampleSphereLight(kC, R, p, rng.next2());
            if (s.pdf == 0.0f) continue;
            glm::dvec3 x = glm::dvec3(p) + double(s.dist) * glm::dvec3(s.dir);
            glm::dvec3 n = (x - glm::dvec3(kC)) / double(R);
            ASSERT_NEAR(glm::length(n), 1.0, 1e-4);  // the point is on the sphere
            double cosL = std::fabs(glm::dot(n, glm::dvec3(s.dir)));
            double areaForm = double(s.dist) * s.dist / (cosL * 4.0 * kPi * R * R);
            ASSERT_NEAR(s.pdf / areaForm, 1.0, 2e-3) << "dist " << s.dist << " cos " << cosL;
        }
    }
}

// In the cone strategy the sampled point is the NEAR intersection of the ray with the sphere.
TEST(LightStats, SphereConeDistanceIsNearIntersection) {
    const float R = 0.7f;
    for (float k : {1.0002f, 1.01f, 2.0f, 100.0f}) {
        vec3 p = kC + (k * R) * glm::normalize(vec3(0.5f, 0.5f, -1.0f));
        UniformSource rng(216);
        for (int i = 0; i < 20000; ++i) {
            gpu::LightSample s = gpu::sampleSphereLight(kC, R, p, rng.next2());
            ASSERT_GT(s.pdf, 0.0f);
            glm::dvec3 x = glm::dvec3(p) + double(s.dist) * glm::dvec3(s.dir);
            ASSERT_NEAR(glm::length(x - glm::dvec3(kC)) / R, 1.0, 1e-4) << k;
            // the point faces p: the normal there points back towards p (or is tangent)
            ASSERT_LE(glm::dot(x - glm::dvec3(kC), glm::dvec3(s.dir)), 1e-4 * R) << k;
        }
    }
}

// Tiny, distant spheres (issue 5: "a small-angle form that stays accurate"): the cone's
// 1 - cos(theta_max) is formed as s2 / (1 + cos) from s2 = (R/d)^2, never as 1 - sqrt(1 - s2),
// which cancels in float (4.6% off at R/d = 1e-3, 0 - an infinite pdf - below R/d ~ 2.4e-4).
// For R/d from 1e-2 to 1e-7: (a) the pdf times the exact solid angle (double) is 1 within 1e-5;
// (b) down to R/d = 1e-5 (a cone of ~170 float ulps of a unit vector) every sampled direction lies
// in the cone (up to the rounding of a float direction) and its point on the sphere, and the directions are uniform over the cone's disk:
// chi-square of (r^2 = sin^2 / s2, phi) on a 10 x 10 grid (uniform up to O(s2) = 1e-6), run at
// statsAlpha() like the rest of the suite (one test of the budget).
TEST(LightStats, SphereConeSmallAngleStaysAccurate) {
    const float R = 1.0e-3f;
    const vec3 p(0.25f, -0.5f, 0.125f);
    const vec3 axis = glm::normalize(vec3(0.3f, 0.8f, -0.52f));
    for (double k : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
        SCOPED_TRACE(k);
        const vec3 c = p + float(k * R) * axis;
        const double d = glm::length(glm::dvec3(c) - glm::dvec3(p));
        const double s2 = (double(R) / d) * (double(R) / d);
        const double omExact = s2 / (1.0 + std::sqrt(1.0 - s2));  // 1 - cos(theta_max), exact in double
        const float sinMaxF = float(double(R) / d);
        const float naive = 1.0f - std::sqrt(1.0f - sinMaxF * sinMaxF);  // the cancelling form
        if (k >= 1e3) EXPECT_GT(std::fabs(naive / omExact - 1.0), 0.04) << "the textbook form should fail here";
        UniformSource rng(219);
        std::vector<glm::dvec2> cells;
        for (int i = 0; i < (k <= 1e5 ? kSamples : 1000); ++i) {
            const gpu::LightSample s = gpu::sampleSphereLight(c, R, p, rng.next2());
            ASSERT_GT(s.pdf, 0.0f);
            ASSERT_NEAR(double(s.pdf) * 2.0 * kPi * omExact, 1.0, 1e-5);
            if (k > 1e5) continue;
            const glm::dvec3 w = glm::dvec3(s.dir) / glm::length(glm::dvec3(s.dir));
            const glm::dvec3 a = (glm::dvec3(c) - glm::dvec3(p)) / d;
            const glm::dvec3 cr = glm::cross(w, a);
            const double sin2 = glm::dot(cr, cr);
            // In the cone, up to the rounding of a float unit vector (~4 eps of angle).
            ASSERT_LE(std::sqrt(sin2), std::sqrt(s2) + 4.0 * std::ldexp(1.0, -24));
            const glm::dvec3 x = glm::dvec3(p) + double(s.dist) * glm::dvec3(s.dir);
            ASSERT_NEAR(glm::length(x - glm::dvec3(c)) / R, 1.0, 2e-2);  // float dist and dir at d = 1e5 R
            if (k == 1e4) {
                // (r^2, phi) in the cone's disk: r^2 = sin^2 / s2, phi from a frame around the axis.
                const glm::dvec3 t = glm::normalize(glm::cross(a, glm::dvec3(1, 0, 0)));
                const glm::dvec3 b = glm::cross(a, t);
                cells.push_back(glm::dvec2(sin2 / s2, std::atan2(glm::dot(w, b), glm::dot(w, t))));
            }
        }
        if (k == 1e4) {
            Grid2D g;
            g.x0 = 0.0;
            g.x1 = 1.0 + 1e-3;
            g.y0 = -kPi;
            g.y1 = kPi;
            g.nx = g.ny = 10;
            EXPECT_TRUE(passesChi2(chi2Test2D(cells, g, [](double r2, double) { return r2 <= 1.0 ? 1.0 / (2.0 * kPi) : 0.0; })));
        }
    }
}

// ---- No NaN or Inf, whatever the geometry
// ---------------------------------------------------------

bool finiteSample(const gpu::LightSample& s) {
    return std::isfinite(s.pdf) && s.pdf >= 0.0f && std::isfinite(s.dist) && s.dist >= 0.0f &&
           std::isfinite(s.dir.x) && std::isfinite(s.dir.y) && std::isfinite(s.dir.z);
}

TEST(LightStats, SphereNumericsNeverProduceNanOrInf) {
    UniformSource rng(217);
    struct Setup {
        vec3 c;
        float R;
    };
    const float nan = std::nanf("");
    for (Setup st : {Setup{vec3(0.0f), 1.0f}, Setup{vec3(1e3f, -2e3f, 5e2f), 1e-3f},
                     Setup{vec3(-3.0f, 4.0f, 1.0f), 1e3f}}) {
        // Distances around every strategy boundary, exactly on the sphere, at the centre, far.
        std::vector<float> rel = {0.0f,
                                  1e-7f,
                                  0.5f,
                                  1.0f - 1e-3f,
                                  1.0f - 1.0001e-4f,
                                  1.0f - 1e-4f,
                                  1.0f - 1e-6f,
                                  1.0f - 6e-8f,
                                  1.0f,
                                  1.0f + 6e-8f,
                                  1.0f + 1e-6f,
                                  1.0f + 1e-4f,
                                  1.0f + 1.0001e-4f,
                                  1.0f + 1e-3f,
                                  2.0f,
                                  1e3f,
                                  1e9f};
        for (float k : rel) {
            for (int j = 0; j < 200; ++j) {
                vec3 p = st.c + (k * st.R) * gpu::sampleUniformSphere(rng.next2());
                for (int i = 0; i < 10; ++i) {
                    gpu::LightSample s = gpu::sampleSphereLight(st.c, st.R, p, rng.next2());
                    ASSERT_TRUE(finiteSample(s)) << k << " R " << st.R;
                    float alone = gpu::pdfSphereLight(st.c, st.R, p, s.dir);
                    ASSERT_TRUE(std::isfinite(alone) && alone >= 0.0f);
                    vec3 randomDir = gpu::sampleUniformSphere(rng.next2());
                    float other = gpu::pdfSphereLight(st.c, st.R, p, randomDir);
                    ASSERT_TRUE(std::isfinite(other) && other >= 0.0f);
                    vec2 inv = gpu::invertSphereLight(st.c, st.R, p, s.dir);
                    ASSERT_TRUE(std::isfinite(inv.x) && std::isfinite(inv.y));
                }
            }
        }
    }
    // Far away: d = 1e6, R = 1e-3 (solid angle ~3e-18 sr): a finite, positive pdf.
    vec3 far(1e6f, 0.0f, 0.0f);
    gpu::LightSample s = gpu::sampleSphereLight(vec3(0.0f), 1e-3f, far, vec2(0.3f, 0.7f));
    ASSERT_TRUE(finiteSample(s));
    EXPECT_GT(s.pdf, 1e16f);
    EXPECT_NEAR(s.dist, 1e6f, 1.0f);
    EXPECT_NEAR(s.dir.x, -1.0f, 1e-6f);
    // Degenerate spheres and NaN positions: no sample.
    for (float R : {0.0f, -1.0f, nan}) {
        gpu::LightSample z =
            gpu::sampleSphereLight(vec3(0.0f), R, vec3(2.0f, 0.0f, 0.0f), vec2(0.5f));
        EXPECT_TRUE(finiteSample(z));
        EXPECT_EQ(z.pdf, 0.0f);
        EXPECT_EQ(
            gpu::pdfSphereLight(vec3(0.0f), R, vec3(2.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f)),
            0.0f);
    }
    gpu::LightSample z =
        gpu::sampleSphereLight(vec3(0.0f), 1.0f, vec3(nan, 0.0f, 0.0f), vec2(0.5f));
    EXPECT_TRUE(finiteSample(z));
    EXPECT_EQ(z.pdf, 0.0f);
}

TEST(LightStats, PlanarNumericsNeverProduceNanOrInf) {
    UniformSource rng(218);
    // p on the quad's plane, on the quad itself, far away; degenerate quads and triangles.
    std::vector<vec3> points = {
        vec3(0.0f, 0.0f, 2.0f),        kQ, kQ + kU, vec3(5.0f, 5.0f, 2.0f), vec3(0.0f, 0.0f, 1e7f),
        vec3(0.0f, 0.0f, 2.0f + 1e-6f)};
    struct Quad {
        vec3 Q, u, v;
    };
    for (Quad q : {Quad{kQ, kU, kV}, Quad{kQ, vec3(0.0f), kV}, Quad{kQ, kU, 2.0f * kU},
                   Quad{kQ, vec3(1e-20f, 0.0f, 0.0f), kV}}) {
        for (const vec3& p : points) {
            for (int i = 0; i < 500; ++i) {
                vec2 xi = rng.next2();
                gpu::LightSample a = gpu::sampleQuadLight(q.Q, q.u, q.v, p, xi);
                gpu::LightSample b = gpu::sampleTriangleLight(q.Q, q.u, q.v, p, xi);
                ASSERT_TRUE(finiteSample(a) && finiteSample(b));
                vec3 d = gpu::sampleUniformSphere(rng.next2());
                for (float f : {gpu::pdfQuadLight(q.Q, q.u, q.v, p, d),
                                gpu::pdfTriangleLight(q.Q, q.u, q.v, p, d),
                                gpu::pdfQuadLight(q.Q, q.u, q.v, p, a.dir),
                                gpu::pdfTriangleLight(q.Q, q.u, q.v, p, b.dir)}) {
                    ASSERT_TRUE(std::isfinite(f) && f >= 0.0f);
                }
            }
        }
    }
    // p in the plane of the quad: every sample is edge-on, no valid sample.
    gpu::LightSample s = gpu::sampleQuadLight(kQ, kU, kV, vec3(5.0f, 5.0f, 2.0f), vec2(0.5f));
    EXPECT_EQ(s.pdf, 0.0f);
}

}  // namespace
