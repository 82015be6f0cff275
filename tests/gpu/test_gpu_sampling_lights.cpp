// The GLSL build of shaders/shared/light_sampling.h equals its C++ build: sampleXLight, pdfXLight
// and invertXLight of quads, triangles and spheres on the device (sampling_test.comp, routines
// 8-10) against vkp::gpu, over near, far, grazing, degenerate and invalid configurations and every
// sphere strategy. The method and the tolerances: see test_gpu_sampling.cpp and sampling_kernel.h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "gpu_env.h"
#include "sampling_kernel.h"
#include "shared/rect_sampling.h"
#include "shared/light_sampling.h"
#include "shared/triangle_sampling.h"
#include "render/light_table.h"
#include "shared/light_pick.h"
#include "stat_suite.h"

namespace vkp::test {
namespace {

namespace gpu = vkp::gpu;
using namespace sampling;
using glm::dvec3;

/// Quads / triangles Q + a e1 + b e2 seen from p: near, far, grazing, from behind, far and tiny,
/// p in the light's plane and on the light itself (no valid sample), degenerate edges.
std::vector<PlanarCase> planarCases() {
    const vec3 q(-1.0f, -0.5f, 2.0f), u(2.0f, 0.0f, 0.0f), v(0.0f, 1.0f, 0.0f);
    return {{q, u, v, {0.2f, 0.1f, 1.7f}},
            {q, u, v, {3.0f, -4.0f, -30.0f}},
            {q, u, v, {0.0f, -3.0f, 2.05f}},
            {q, u, v, {0.0f, -3.0f, 2.0001f}},
            {q, u, v, {0.0f, 0.0f, 1e7f}},
            {q, u, v, {5.0f, 5.0f, 2.0f}},
            {q, u, v, {0.0f, 0.0f, 2.0f}},
            {q, u, v, q},
            {{0.5f, 0.2f, -1.0f}, {1.5f, 0.2f, 0.6f}, {0.9f, 1.1f, -0.2f}, {1.0f, 0.5f, 1.0f}},
            {{1000.0f, -2000.0f, 500.0f}, {1e-3f, 0.0f, 0.0f}, {0.0f, 1e-3f, 2e-4f}, {0.0f, 0.0f, 0.0f}},
            {q, vec3(0.0f), v, {0.2f, 0.1f, 1.7f}},
            {q, u, 2.0f * u, {0.2f, 0.1f, 1.7f}},
            {q, vec3(1e-20f, 0.0f, 0.0f), v, {0.2f, 0.1f, 1.7f}}};
}

/// An invalid light sample is exactly dir = +z, dist = 0, pdf = 0 in both builds.
void expectSameInvalidSample(Compare& c, const Out& d) {
    if (!(d.o[0] == vec4(0.0f, 0.0f, 1.0f, 0.0f) && d.o[1].x == 0.0f)) c.fail("invalid sample is not (+z, 0, 0)");
}

/// Light routines: the sample (dir, dist, pdf) against the host's; pdfXLight and invertXLight of the
/// device's direction against the host's of the same direction. nearEdge(it): the sample may lie on
/// the light's boundary (the ray cast back may then hit in one build and miss in the other).
/// distRel(it, host): relative tolerance of dist. azimuthTol(it, inverse): tolerance of an inverse's
/// y when it is an azimuth (sphere lights), nullptr otherwise.
Comparator lightComparator(const std::function<float(const Item&, vec3)>& pdf, const std::function<vec2(const Item&, vec3)>& invert,
                           const std::function<bool(const Item&)>& nearEdge, const std::function<double(const Item&, const Out&)>& distRel,
                           const std::function<double(const Item&, vec2)>& azimuthTol) {
    return [=](Compare& c, const Item& it, const Out& d, const Out& h) {
        const bool dv = d.o[1].x > 0.0f, hv = h.o[1].x > 0.0f;
        if (dv != hv) {
            if (nearEdge(it))
                c.flip();
            else
                c.fail("valid in one build only");
        } else if (dv) {
            for (int k = 0; k < 3; ++k) c.near("dir", d.o[0][k], h.o[0][k], kDirTol);
            c.near("dist", d.o[0].w, h.o[0].w, 0.0, distRel(it, h));
            c.near("pdf", d.o[1].x, h.o[1].x, 0.0, 1e-5);
        } else {
            expectSameInvalidSample(c, d);
        }
        const vec3 dir = xyz(d.o[0]);
        const float p = pdf(it, dir);
        const vec2 inv = invert(it, dir);
        if (((d.o[1].y == 0.0f) != (p == 0.0f) || (d.o[1].z == -1.0f) != (inv.x == -1.0f)) && nearEdge(it)) {
            c.flip();
            return;
        }
        c.near("pdfAlone", d.o[1].y, p, 0.0, 1e-5);
        c.near("invert.x", d.o[1].z, inv.x, kInvTol);
        if (azimuthTol && inv.x >= 0.0f)
            c.nearCircular("invert.y", d.o[1].w, inv.y, azimuthTol(it, inv));
        else
            c.near("invert.y", d.o[1].w, inv.y, kInvTol);
    };
}

void checkPlanar(VulkanDevice& dev, bool tri) {
    std::vector<Item> items;
    std::uint32_t seed = tri ? 60 : 40;
    for (const PlanarCase& pc : planarCases())
        for (vec2 xi : uPairs(seed++, kRandomItems / 13)) items.push_back(item(vec4(pc.q, xi.x), vec4(pc.e1, xi.y), vec4(pc.e2, 0.0f), vec4(pc.p, 0.0f)));
    // xi on an edge of [0,1)^2 puts the sample on the light's boundary (triangle: xi.x = 0 is the
    // vertex v0, xi.x -> 1 the edge a + b = 1, xi.y = 0 or -> 1 the edges b = 0, a = 0).
    auto nearEdge = [](const Item& it) { return std::min(edgeDistance(it.in[0].w), edgeDistance(it.in[1].w)) < 1e-4; };
    // dist = length(x - p) with x and p the same in both builds: only the last ulp of sqrt.
    auto distRel = [](const Item&, const Out&) { return 1e-6; };
    auto pdf = [tri](const Item& it, vec3 dir) {
        const vec3 a = xyz(it.in[0]), b = xyz(it.in[1]), e = xyz(it.in[2]), p = xyz(it.in[3]);
        return tri ? gpu::pdfTriangleLight(a, b, e, p, dir) : gpu::pdfQuadLight(a, b, e, p, dir);
    };
    auto invert = [tri](const Item& it, vec3 dir) {
        const vec3 a = xyz(it.in[0]), b = xyz(it.in[1]), e = xyz(it.in[2]), p = xyz(it.in[3]);
        return tri ? gpu::invertTriangleLight(a, b, e, p, dir) : gpu::invertQuadLight(a, b, e, p, dir);
    };
    checkRoutine(dev, tri ? kTriLight : kQuadLight, tri ? "triangle light" : "quad light", items,
                 lightComparator(pdf, invert, nearEdge, distRel, nullptr));
}

TEST(GpuSampling, QuadLightMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkPlanar(dev, false);
}

TEST(GpuSampling, TriangleLightMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkPlanar(dev, true);
}

/// Runs a planar solid-angle light routine (out1.z = 1 when it used its solid-angle strategy, else
/// its area fallback) over the planar cases and compares device with host: the same strategy
/// (except where `ambiguous` says rounding may pick either), samples and pdfs within tolerances.
/// Directions within 2e-3, pdfs within 1e-4 relative: the warps go through acos/asin, atan, sin and
/// cos (each ~1 ulp apart between the builds) and divisions that amplify them for a point almost
/// in the light's plane (worst seen: 2e-4 and 2e-5 for rectangles).
///
/// A third of the items pass minSize 0 (solid angle wherever it is precise), a third half the
/// light's apparent size (the same) and a third twice it (area sampling by the size switch of
/// `--light-sampling auto`): the switch must take the same branch in both builds.
void checkSolidAngleLight(VulkanDevice& dev, Routine r, const char* name, std::uint32_t seed,
                          const std::function<bool(const Item&)>& ambiguous) {
    const bool tri = r == kSphTriLight;
    std::vector<Item> items;
    for (const PlanarCase& pc : planarCases()) {
        const float area = tri ? 0.5f * glm::length(glm::cross(pc.e1, pc.e2)) : glm::length(glm::cross(pc.e1, pc.e2));
        const vec3 centre = tri ? pc.q + (pc.e1 + pc.e2) * (1.0f / 3.0f) : pc.q + 0.5f * (pc.e1 + pc.e2);
        const float size = gpu::apparentSize(area, centre, pc.p);
        int k = 0;
        for (vec2 xi : uPairs(seed++, kRandomItems / 13)) {
            const float minSize = (k % 3 == 0) ? 0.0f : (k % 3 == 1) ? 0.5f * size : 2.0f * size;
            ++k;
            items.push_back(item(vec4(pc.q, xi.x), vec4(pc.e1, xi.y), vec4(pc.e2, minSize), vec4(pc.p, 0.0f)));
        }
    }
    int solidAngle = 0, switchedToArea = 0, compared = 0;
    checkRoutine(dev, r, name, items, [&](Compare& c, const Item& it, const Out& d, const Out& h) {
        if (d.o[1].z != h.o[1].z) return ambiguous(it) ? c.flip() : c.fail("strategy differs");
        ++compared;
        solidAngle += d.o[1].z != 0.0f;
        const bool large = tri ? gpu::triangleLargeEnough(xyz(it.in[0]), xyz(it.in[1]), xyz(it.in[2]), xyz(it.in[3]), it.in[2].w)
                               : gpu::rectLargeEnough(xyz(it.in[0]), xyz(it.in[1]), xyz(it.in[2]), xyz(it.in[3]), it.in[2].w);
        switchedToArea += !large;
        if (!large && d.o[1].z != 0.0f) return c.fail("solid angle below minSize");
        if ((d.o[1].x > 0.0f) != (h.o[1].x > 0.0f)) {
            if (std::min(edgeDistance(it.in[0].w), edgeDistance(it.in[1].w)) < 1e-4) return c.flip();
            return c.fail("valid in one build only");
        }
        if (d.o[1].x == 0.0f) return expectSameInvalidSample(c, d);
        for (int k = 0; k < 3; ++k) c.near("dir", d.o[0][k], h.o[0][k], 2e-3);
        c.near("pdf", d.o[1].x, h.o[1].x, 0.0, 1e-4);
        if (d.o[1].y > 0.0f && h.o[1].y > 0.0f) c.near("pdfAlone", d.o[1].y, h.o[1].y, 0.0, 1e-4);
    });
    // Both strategies and the size switch are really exercised: of the items whose minSize allows
    // solid-angle sampling (two thirds) at least a sixth use it; a third are switched to area.
    EXPECT_GT(solidAngle, (compared - switchedToArea) / 6);
    EXPECT_GT(switchedToArea, compared / 4);
}

// Triangles sampled uniformly in solid angle (triangle_sampling.h, Arvo 1995). The strategies may
// differ only where S sits at a threshold or is ~0 (a point in the triangle's plane).
TEST(GpuSampling, SphericalTriangleLightMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkSolidAngleLight(dev, kSphTriLight, "spherical triangle light", 180, [](const Item& it) {
        const double S = gpu::triangleLightSolidAngle(xyz(it.in[0]), xyz(it.in[1]), xyz(it.in[2]), xyz(it.in[3]));
        return std::abs(S - gpu::TRI_MIN_SOLID_ANGLE) < 1e-5 || std::abs(S - gpu::TRI_MAX_SOLID_ANGLE) < 1e-4 || S < 1e-6;
    });
}

// Rectangles sampled uniformly in solid angle (rect_sampling.h). From a point in the light's own
// plane the solid angle is 0 or 2 pi, exactly at the strategy's limits: rounding may choose either
// there, and nowhere else.
TEST(GpuSampling, RectLightMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkSolidAngleLight(dev, kRectLight, "rect light", 80, [](const Item& it) {
        const gpu::SphericalRect r = gpu::sphericalRectInit(xyz(it.in[0]), xyz(it.in[1]), xyz(it.in[2]), xyz(it.in[3]));
        return std::abs(r.z0) <= 1e-6f * (std::abs(r.x0) + std::abs(r.y0) + 1.0f);
    });
}

/// Sphere lights seen from outside (near, just outside, far, far and tiny), from the surface band
/// (on it, just outside, just inside), from inside (near the surface, off centre, at the centre),
/// huge spheres, invalid ones (R = 0, R < 0, R = NaN, p = NaN), and random points at 0..3 radii,
/// kept 1e-5 (relative) away from the strategy boundaries d = R (1 +- 1e-4) so that both builds
/// pick the same strategy.
std::vector<SphereCase> sphereCases() {
    const vec3 c(0.3f, -0.2f, 1.0f);
    const vec3 dir = glm::normalize(vec3(1.0f, 2.0f, 3.0f));
    const float nan = std::nanf("");
    std::vector<SphereCase> v = {{c, 1.0f, c + vec3(0.0f, 1.5f, 0.0f)},
                                 {c, 2.0f, c + 2.002f * glm::normalize(vec3(1.0f, -2.0f, 0.5f))},
                                 {c, 0.5f, c + vec3(15.0f, -10.0f, 25.0f) * 0.65f},
                                 {vec3(0.0f), 1e-3f, vec3(1e6f, 0.0f, 0.0f)},
                                 {c, 1.5f, c + 1.5f * dir},
                                 {c, 1.5f, c + 1.5f * 1.00005f * dir},
                                 {c, 1.5f, c + 1.5f * 0.99995f * dir},
                                 {c, 1.0f, c + 0.999f * glm::normalize(vec3(-1.0f, 0.5f, 0.25f))},
                                 {c, 1.0f, c + vec3(0.4f, -0.3f, 0.2f)},
                                 {c, 1.0f, c},
                                 {vec3(-3.0f, 4.0f, 1.0f), 1e3f, vec3(-3.0f, 4.0f, 1.0f) + 500.0f * dir},
                                 {vec3(-3.0f, 4.0f, 1.0f), 1e3f, vec3(-3.0f, 4.0f, 1.0f) + 2000.0f * dir},
                                 {c, 0.0f, c + dir},
                                 {c, -1.0f, c + dir},
                                 {c, nan, c + dir},
                                 {c, 1.0f, vec3(nan, 0.0f, 0.0f)},
                                 {vec3(0.0f), 1e-20f, vec3(1e5f, 0.0f, 0.0f)},  // (R/d)^2 underflows to 0
                                 {vec3(0.0f), 1e-20f, vec3(0.0f, 1.0f, 0.0f)}};  // (R/d)^2 subnormal
    UniformSource rng(80);
    while (v.size() < 42) {
        const float R = 0.1f + 2.0f * rng.next();
        const vec3 p = c + (3.0f * R * rng.next()) * gpu::sampleUniformSphere(rng.next2());
        const double k = glm::length(c - p) / R;
        if (std::fabs(k - (1.0 + 1e-4)) > 1e-5 && std::fabs(k - (1.0 - 1e-4)) > 1e-5) v.push_back({c, R, p});
    }
    return v;
}

TEST(GpuSampling, SphereLightMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    std::uint32_t seed = 81;
    for (const SphereCase& s : sphereCases())
        for (vec2 xi : uPairs(seed++, kRandomItems / 42)) items.push_back(item(vec4(s.c, s.R), vec4(xi, 0.0f, 0.0f), vec4(0.0f), vec4(s.p, 0.0f)));
    auto strategy = [](const Item& it) { return gpu::sphereLightStrategy(glm::length(xyz(it.in[0]) - xyz(it.in[3])), it.in[0].w); };
    // Cone and surface: xi.x -> 1 is the sphere's silhouette, where the sample grazes the sphere
    // (cone: its pdf-alone test sin^2 <= sin^2 theta_max is decided by rounding; surface band
    // outside the sphere: a direction at the tangent plane may miss it in one build only).
    auto nearEdge = [strategy](const Item& it) {
        const std::uint32_t s = strategy(it);
        return (s == gpu::SPHERE_LIGHT_CONE || s == gpu::SPHERE_LIGHT_SURFACE) && it.in[1].x > 1.0f - 1e-3f;
    };
    // The cone's near intersection t = (d - R)(d + R) / (d cos + R sqrt(1 - k)), k = sin^2 / sin^2
    // theta_max: towards the silhouette (k -> 1) sqrt(1 - k) magnifies the last-ulp differences of
    // k (sin^2 + cos^2 of the azimuth is 1 only up to rounding; dK = 2e-6 allowed, ~5e-7 seen) to
    // min(dK / (2 sqrt(1 - k)), sqrt(dK)), and t by R times that over the denominator. Elsewhere
    // dist differs by a few ulps.
    auto distRel = [strategy](const Item& it, const Out&) {
        if (strategy(it) != gpu::SPHERE_LIGHT_CONE) return 1e-5;
        const float R = it.in[0].w, d = glm::length(xyz(it.in[0]) - xyz(it.in[3]));
        const float s2 = (R / d) * (R / d);
        const vec3 w = gpu::sampleUniformCone(vec2(it.in[1]), gpu::coneOneMinusCos(s2));
        const double k = std::min(1.0, (double(w.x) * w.x + double(w.y) * w.y) / s2);
        const double dK = 2e-6, sq = std::sqrt(1.0 - k), dSq = std::min(dK / (2.0 * sq), std::sqrt(dK));
        return 1e-5 + R * dSq / (d * w.z + R * sq);
    };
    // The azimuth of a direction at polar radius r (sine of its angle to the strategy's axis) moves
    // by delta / (2 pi r) when the direction moves by delta: 2e-7 / r allows delta ~1e-6. r from the
    // host's inverse: cone 1 - cos = u.x oneMinusCosMax, surface r^2 = u.x (cosine hemisphere),
    // inside z = 1 - 2 u.x (uniform sphere of normals).
    auto azimuthTol = [strategy](const Item& it, vec2 inv) {
        const float R = it.in[0].w, d = glm::length(xyz(it.in[0]) - xyz(it.in[3]));
        double r = 0.0;
        if (strategy(it) == gpu::SPHERE_LIGHT_CONE) {
            const double t = inv.x * gpu::coneOneMinusCos((R / d) * (R / d));
            r = std::sqrt(t * (2.0 - t));
        } else if (strategy(it) == gpu::SPHERE_LIGHT_SURFACE) {
            r = std::sqrt(double(inv.x));
        } else {
            r = 2.0 * std::sqrt(double(inv.x) * (1.0 - inv.x));
        }
        return kInvTol + 2e-7 / r;
    };
    auto pdf = [](const Item& it, vec3 dir) { return gpu::pdfSphereLight(xyz(it.in[0]), it.in[0].w, xyz(it.in[3]), dir); };
    auto invert = [](const Item& it, vec3 dir) { return gpu::invertSphereLight(xyz(it.in[0]), it.in[0].w, xyz(it.in[3]), dir); };
    checkRoutine(dev, kSphereLight, "sphere light", items, lightComparator(pdf, invert, nearEdge, distRel, azimuthTol));
}

}  // namespace
// Lights picked by power on the device (issue 5: "the probability the shader reports for a light
// equals the probability with which it is picked", pbrt's test): the GLSL build of the alias pick
// (light_pick.h, as lib/lights.glsl's pickLightPower uses it) on a table built by the host
// (render/light_table.cpp) for 8 lights of very different power, one of them 0. (a) Every pick
// equals the C++ build's for the same u; (b) the frequencies of 200k device picks match the
// probabilities the picked entries report: chi-square at statsAlpha() (the stats suite's Sidak
// share; fixed seed); (c) the zero-power light is never picked.
TEST(GpuSamplingLights, AliasPickFrequenciesMatchReportedProbabilities) {
    VKP_REQUIRE_DEVICE(dev);
    const std::vector<double> w = {3.0, 0.0, 1.0, 12.0, 0.25, 5.0, 7e-3, 40.0};
    const AliasTable t = buildAliasTable(w);
    const std::uint32_t n = std::uint32_t(w.size());
    const int picks = 200000;
    std::vector<Item> items;
    UniformSource rng(220);
    for (int k = 0; k < picks; ++k)
        items.push_back(item(vec4(rng.next(), asFloat(n), asFloat(std::uint32_t(picks)), 0.0f)));
    std::vector<gpu::GpuLight> lights(n);
    for (std::uint32_t j = 0; j < n; ++j) {
        lights[j].l0 = vec4(0.0f, t.probability[j], t.threshold[j], asFloat(t.alias[j]));
        items.push_back(item(lights[j].l0));
    }
    const std::vector<Out> out = runSamplingKernel(dev, kLightPick, items);
    std::vector<double> observed(n, 0.0), expected(n, 0.0);
    int differ = 0;
    for (int k = 0; k < picks; ++k) {
        const std::uint32_t li = asUint(out[k].o[0].x);
        ASSERT_LT(li, n);
        float frac;
        const std::uint32_t col = gpu::aliasColumn(items[k].in[0].x, n, frac);
        differ += li != gpu::aliasResolve(col, frac, lights[col]);
        ASSERT_EQ(out[k].o[0].y, lights[li].l0.y) << "the reported probability is the picked entry's";
        observed[li] += 1.0;
    }
    EXPECT_EQ(differ, 0) << "device and host picks differ";
    EXPECT_EQ(observed[1], 0.0) << "a light of zero power was picked";
    for (std::uint32_t j = 0; j < n; ++j) expected[j] = picks * double(lights[j].l0.y);
    EXPECT_TRUE(passesChi2(chi2Test(observed, expected)));
    expectNoValidationMessages(dev);
}

}  // namespace vkp::test
