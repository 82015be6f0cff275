// The shared sampling code compiled as GLSL equals the same code compiled as C++.
// shaders/shared/{rng,onb,sampling,light_sampling,scatter}.h are checked statistically as C++ by
// tests/stats, but the kernels run their GLSL build. Every routine of the device test kernel
// shaders/tests/sampling_test.comp (ids 0..14; harness: sampling_kernel.h) runs here on a few
// thousand inputs (fixed seeds, plus edge cases: u = 0 and u = 1 - 2^-24, poles, grazing and
// normal incidence, critical angles, u exactly at a reflect probability, empty and tiny cones) and
// is compared with vkp::gpu called on the same inputs:
//   - RNG outputs bit for bit;
//   - samples (directions, points, distances, pdfs returned with a sample) with the C++ sample;
//   - evaluations (pdfX(dir), invertX(dir)) with C++ evaluated at the DEVICE's sample, so that a
//     last-ulp difference of the sample is not amplified by an ill-conditioned inverse;
//   - no NaN or Inf output in either build, for any input used.
// Tolerances: sampling_kernel.h (shared ones, with the differences measured on lavapipe) and at
// each comparison; where the problem itself is ill-conditioned (the sphere's silhouette, the
// critical angle, the azimuth near a pole) the tolerance follows the condition number, stated
// there. Where a last-ulp difference may legitimately flip a branch (u at a Fresnel threshold, a
// mirror ray in the tangent plane, a sample on a light's edge or on a cone's rim), either branch is
// accepted there and nowhere else, and the flips are counted in the printed summary.
// Lights: test_gpu_sampling_lights.cpp; chi-square tests of the device's samples:
// test_gpu_sampling_stats.cpp; the glTF BRDF (microfacet.h, ids 16-18):
// test_gpu_sampling_microfacet.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gpu_env.h"
#include "sampling_kernel.h"
#include "shared/scatter.h"
#include "stat_suite.h"

namespace vkp::test {
namespace {

namespace gpu = vkp::gpu;
using namespace sampling;
using glm::dvec3;

// ---- RNG and ONB -----------------------------------------------------------------------------

TEST(GpuSampling, RngIsBitExact) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const std::uint32_t edges[] = {0u, 1u, 2u, 0x7f800001u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        items.push_back(item(vec4(asFloat(a), asFloat(b), asFloat(c), 0.0f)));
    };
    for (std::uint32_t a : edges)
        for (std::uint32_t b : edges)
            for (std::uint32_t c : edges) add(a, b, c);
    for (std::uint32_t pixel = 0; pixel < 40; ++pixel)
        for (std::uint32_t s = 0; s < 25; ++s) add(pixel, s, 42u);
    std::mt19937 gen(11);
    for (int i = 0; i < kRandomItems; ++i) {
        const auto a = static_cast<std::uint32_t>(gen()), b = static_cast<std::uint32_t>(gen());
        add(a, b, static_cast<std::uint32_t>(gen()));
    }
    checkRoutine(dev, kRng, "rng", items, [](Compare& c, const Item&, const Out& d, const Out& h) {
        for (int k = 0; k < 8; ++k) c.bitsEqual("draw", d.o[k / 4][k % 4], h.o[k / 4][k % 4]);
    });
}

// The Sobol' sampler (sobol.h) and the sample stream (sample_stream.h): GLSL equals C++ bit for
// bit on edge keys and 20k random (pixel, index, seed, group) keys, groups 0..63.
TEST(GpuSampling, SobolIsBitExact) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const std::uint32_t edges[] = {0u, 1u, 3u, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu};
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t g) {
        items.push_back(item(vec4(asFloat(a), asFloat(b), asFloat(c), asFloat(g))));
    };
    for (std::uint32_t a : edges)
        for (std::uint32_t b : edges)
            for (std::uint32_t c : edges)
                for (std::uint32_t g : {0u, 1u, 9u}) add(a, b, c, g);
    for (std::uint32_t pixel = 0; pixel < 16; ++pixel)
        for (std::uint32_t s = 0; s < 64; ++s) add(pixel, s, 42u, s % 20u);
    std::mt19937 gen(17);
    for (int i = 0; i < kRandomItems; ++i) {
        const auto a = static_cast<std::uint32_t>(gen()), b = static_cast<std::uint32_t>(gen() >> (gen() % 32u));
        const auto c = static_cast<std::uint32_t>(gen());
        add(a, b, c, static_cast<std::uint32_t>(gen() % 64u));
    }
    checkRoutine(dev, kSobol, "sobol", items, [](Compare& c, const Item&, const Out& d, const Out& h) {
        for (int k = 0; k < 8; ++k) c.bitsEqual("value", d.o[k / 4][k % 4], h.o[k / 4][k % 4]);
    });
}

TEST(GpuSampling, OnbMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    UniformSource rng(12);
    const std::vector<vec3> normals = unitNormals(13, kRandomItems);
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const vec3 n = normals[i];
        const vec3 v = 4.0f * rng.next3() - vec3(2.0f);
        items.push_back(item(vec4(n, 0.0f), vec4(v, 0.0f)));
        if (i < 12)
            for (vec3 s : {vec3(0.0f), n, vec3(1, 0, 0), vec3(3, -1, 2)}) items.push_back(item(vec4(n, 0.0f), vec4(s, 0.0f)));
    }
    // The frame's vectors come from one division (a = -1 / (sgn + n.z), |a| <= 1): ~1 ulp each.
    checkRoutine(dev, kOnb, "onb", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const double tol = 1e-6 * (1.0 + glm::length(xyz(it.in[1])));
        for (int k = 0; k < 3; ++k) c.near("toWorld", d.o[0][k], h.o[0][k], tol);
        for (int k = 0; k < 3; ++k) c.near("toLocal", d.o[1][k], h.o[1][k], tol);
    });
}

// ---- Direction and point warps -------------------------------------------------------------

/// A warp's sample (out0.xyz, pdf out0.w) against the host's; its inverse (out1) against the host's
/// inverse of the DEVICE's sample. The azimuth of a point on the axis (x = y = 0) does not matter
/// to the round trip: there only its range is checked (its documented value, 0, is checked by
/// PoleAzimuthIsZeroAsDocumented). pdfFlip(it, host): a pdf that may be 0 in one build only.
Comparator warpComparator(const std::function<vec2(vec3, const Item&)>& invert,
                          const std::function<bool(const Item&, const Out&)>& pdfFlip = nullptr) {
    return [=](Compare& c, const Item& it, const Out& d, const Out& h) {
        for (int k = 0; k < 3; ++k) c.near("sample", d.o[0][k], h.o[0][k], kDirTol);
        if ((d.o[0].w == 0.0f) != (h.o[0].w == 0.0f) && pdfFlip && pdfFlip(it, h))
            c.flip();
        else
            c.near("pdf", d.o[0].w, h.o[0].w, 0.0, kPdfRel);
        const vec3 w = xyz(d.o[0]);
        const vec2 inv = invert(w, it);
        c.near("invert.x", d.o[1].x, inv.x, kInvTol);
        if (w.x == 0.0f && w.y == 0.0f) {
            if (!(d.o[1].y >= 0.0f && d.o[1].y < 1.0f)) c.fail("azimuth on the axis out of [0,1)");
        } else {
            c.nearCircular("invert.y", d.o[1].y, inv.y, kInvTol);
        }
    };
}

std::vector<Item> warpItems(std::uint32_t seed, int n, float z = 0.0f) {
    std::vector<Item> items;
    for (vec2 u : uPairs(seed, n)) items.push_back(item(vec4(u, z, 0.0f)));
    return items;
}

TEST(GpuSampling, CosineHemisphereMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkRoutine(dev, kCosineHemi, "cosine hemisphere", warpItems(21, kRandomItems),
                 warpComparator([](vec3 w, const Item&) { return gpu::invertCosineHemisphere(w); }));
}

TEST(GpuSampling, UniformSphereMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkRoutine(dev, kUniformSphere, "uniform sphere", warpItems(22, kRandomItems),
                 warpComparator([](vec3 w, const Item&) { return gpu::invertUniformSphere(w); }));
}

TEST(GpuSampling, UniformHemisphereMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    checkRoutine(dev, kUniformHemi, "uniform hemisphere", warpItems(23, kRandomItems),
                 warpComparator([](vec3 w, const Item&) { return gpu::invertUniformHemisphere(w); }));
}

TEST(GpuSampling, UniformConeMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const float s5 = std::sin(float(5.0 * kPi / 180.0));
    std::uint32_t seed = 24;
    for (float om : {2.0f, 1.5f, 1.0f, 0.5f, gpu::coneOneMinusCos(s5 * s5), 1e-2f, 1e-4f, 1e-7f, 1e-10f, 1e-20f}) {
        std::vector<Item> part = warpItems(seed++, kRandomItems / 10, om);
        items.insert(items.end(), part.begin(), part.end());
    }
    // At the rim (u.x -> 1) the sample's 1 - cos(theta) equals oneMinusCosMax up to rounding, so
    // pdfUniformCone of the sample may be 0 in one build (sin^2 + cos^2 of phi is not exactly 1).
    checkRoutine(dev, kUniformCone, "uniform cone", items,
                 warpComparator([](vec3 w, const Item& it) { return gpu::invertUniformCone(w, it.in[0].z); },
                                [](const Item& it, const Out&) { return it.in[0].x > 1.0f - 1e-4f; }));
}

// An empty cone (oneMinusCosMax = 0, for which pdfUniformCone is documented to return 0): the
// sample is +z and its inverse divides 0 by 0. glm::min(NaN, 1) returns NaN on the host, GLSL's
// min returns 1 on lavapipe: the two builds must not disagree, and neither may return NaN.
TEST(GpuSampling, UniformConeInverseOfEmptyConeIsFinite) {
    VKP_REQUIRE_DEVICE(dev);
    checkRoutine(dev, kUniformCone, "empty cone", warpItems(35, 10, 0.0f),
                 warpComparator([](vec3 w, const Item& it) { return gpu::invertUniformCone(w, it.in[0].z); }));
}

// azimuthToUnit documents "(0,0) maps to 0". Samples on the pole (u.x = 0) are (+-0, +-0, 1),
// depending on the sign of cos / sin of the azimuth; their inverse azimuth must be 0 in both builds.
// GLSL leaves atan(0, 0) undefined (lavapipe: 3 pi / 4, i.e. 0.375), and C++'s atan2(+-0, -0) is
// +-pi (0.5), so the documented value needs an explicit case for x = y = 0.
TEST(GpuSampling, PoleAzimuthIsZeroAsDocumented) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    for (float uy : {0.0f, 0.2f, 0.3f, 0.6f, 0.8f}) items.push_back(item(vec4(0.0f, uy, 0.0f, 0.0f)));
    const std::vector<Out> d = runSamplingKernel(dev, kCosineHemi, items);
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Out h = hostSamplingKernel(kCosineHemi, items[i]);
        SCOPED_TRACE(testing::Message() << "u = (0, " << items[i].in[0].y << "), sample (" << h.o[0].x << ", " << h.o[0].y << ", 1)");
        EXPECT_EQ(d[i].o[1].y, 0.0f) << "device";
        EXPECT_EQ(h.o[1].y, 0.0f) << "host";
    }
    expectNoValidationMessages(dev);
}

TEST(GpuSampling, UniformDiskMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items = warpItems(25, kRandomItems);
    checkRoutine(dev, kUniformDisk, "uniform disk", items, [](Compare& c, const Item&, const Out& d, const Out& h) {
        for (int k = 0; k < 2; ++k) c.near("sample", d.o[0][k], h.o[0][k], kDirTol);
        const vec2 q(d.o[0].x, d.o[0].y);
        // A sample on the rim (|a| or |b| = 1) has |q|^2 = 1 up to rounding: pdf 1/pi or 0.
        const double r2 = double(h.o[0].x) * h.o[0].x + double(h.o[0].y) * h.o[0].y;
        if ((d.o[0].w == 0.0f) != (h.o[0].w == 0.0f) && std::fabs(r2 - 1.0) < 1e-5)
            c.flip();
        else
            c.near("pdf", d.o[0].w, h.o[0].w, 0.0, kPdfRel);
        const vec2 inv = gpu::invertUniformDisk(q);
        c.near("invert.x", d.o[1].x, inv.x, kInvTol);
        c.near("invert.y", d.o[1].y, inv.y, kInvTol);
    });
}

TEST(GpuSampling, UniformBallMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    for (float a : kEdgeU)
        for (float b : kEdgeU)
            for (float z : kEdgeU) items.push_back(item(vec4(a, b, z, 0.0f)));
    UniformSource rng(26);
    for (int i = 0; i < kRandomItems; ++i) items.push_back(item(vec4(rng.next3(), 0.0f)));
    checkRoutine(dev, kUniformBall, "uniform ball", items, [](Compare& c, const Item&, const Out& d, const Out& h) {
        for (int k = 0; k < 3; ++k) c.near("sample", d.o[0][k], h.o[0][k], kDirTol);
        const vec3 q = xyz(d.o[0]);
        if ((d.o[0].w == 0.0f) != (h.o[0].w == 0.0f) && std::fabs(glm::length(dvec3(xyz(h.o[0]))) - 1.0) < 1e-5)
            c.flip();
        else
            c.near("pdf", d.o[0].w, h.o[0].w, 0.0, kPdfRel);
        const vec3 inv = gpu::invertUniformBall(q);
        c.near("invert.x", d.o[1].x, inv.x, kInvTol);
        if (q.x == 0.0f && q.y == 0.0f) {
            if (!(d.o[1].y >= 0.0f && d.o[1].y < 1.0f)) c.fail("azimuth on the axis out of [0,1)");
        } else {
            c.nearCircular("invert.y", d.o[1].y, inv.y, kInvTol);
        }
        c.near("invert.z", d.o[1].z, inv.z, kInvTol);
    });
}

// ---- Materials -------------------------------------------------------------------------------

TEST(GpuSampling, LambertianMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const std::vector<vec3> normals = unitNormals(90, kRandomItems / 2);
    UniformSource rng(91);
    const std::vector<vec2> edges = uPairs(92, 0);
    for (std::size_t i = 0; i < normals.size(); ++i) {
        items.push_back(item(vec4(normals[i], 0.0f), vec4(rng.next2(), 0.0f, 0.0f)));
        items.push_back(item(vec4(normals[i], 0.0f), vec4(edges[i % edges.size()], 0.0f, 0.0f)));
    }
    checkRoutine(dev, kLambertian, "lambertian", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const vec3 n = xyz(it.in[0]), w = xyz(d.o[0]);
        for (int k = 0; k < 3; ++k) c.near("sample", d.o[0][k], h.o[0][k], kDirTol);
        c.near("pdf", d.o[0].w, gpu::pdfLambertian(n, w), 1e-9, kPdfRel);
        // Inverse of the device's direction: the local (x, y) come from dot products with the
        // frame, so the azimuth at polar radius r = sqrt(u.x) is good to ~1e-7 / (2 pi r).
        const vec2 inv = gpu::invertLambertian(n, w);
        c.near("invert.x", d.o[1].x, inv.x, kInvTol);
        c.nearCircular("invert.y", d.o[1].y, inv.y, kInvTol + 2e-7 / std::sqrt(double(inv.x)));
    });
}

TEST(GpuSampling, MetalMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    UniformSource rng(100);
    const std::vector<vec3> normals = unitNormals(101, kRandomItems);
    const float fuzzes[] = {0.0f, 0.05f, 0.5f, 1.0f, 1.7f, -0.3f};
    const double grazing[] = {0.0, 89.9, 89.999, 90.0};  // degrees; 90: dIn in the tangent plane
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const vec3 n = normals[i];
        const gpu::Onb f = gpu::onbFromNormal(n);
        vec3 local = -gpu::sampleUniformHemisphere(rng.next2());  // towards the surface
        if (i % 10 < 4) {
            const double th = grazing[i % 10] * kPi / 180.0;
            local = vec3(float(std::sin(th)), 0.0f, -float(std::cos(th)));
        }
        const vec3 dIn = gpu::toWorld(f, local) * (i % 3 == 0 ? 2.5f : 1.0f);  // not always unit
        vec3 u3 = rng.next3();
        if (i % 7 == 0) u3 = vec3(kEdgeU[i % 6], kEdgeU[(i / 6) % 6], kEdgeU[(i / 36) % 6]);
        items.push_back(item(vec4(dIn, 0.0f), vec4(n, fuzzes[i % 6]), vec4(u3, 0.0f)));
    }
    checkRoutine(dev, kMetal, "metal", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const vec3 n = xyz(it.in[1]);
        const dvec3 r = glm::reflect(glm::normalize(dvec3(xyz(it.in[0]))), dvec3(n));
        const dvec3 o = r + double(glm::clamp(it.in[1].w, 0.0f, 1.0f)) * dvec3(gpu::sampleUniformBall(xyz(it.in[2])));
        // Absorbed iff the fuzzed ray is not above the surface: undecided by rounding when it lies
        // in the tangent plane (o . n ~ 0, e.g. grazing incidence without fuzz).
        if (d.o[0].w != h.o[0].w) {
            if (std::fabs(glm::dot(o, dvec3(n))) < 1e-5 * glm::length(o))
                c.flip();
            else
                c.fail("absorbed in one build only");
            return;
        }
        // normalize(o): an ulp of the sum r + fuzz b is magnified by 1 / |o| (|o| -> 0 when the ball
        // point cancels the mirror direction).
        const double tol = h.o[0].w != 0.0f ? kDirTol : kDirTol + 2e-7 / glm::length(o);
        for (int k = 0; k < 3; ++k) c.near("dir", d.o[0][k], h.o[0][k], tol);
    });
}

/// Reflect probability and sin^2 of the refraction angle, as scatterDielectric computes them (in
/// double): the quantities that decide its branch.
struct DielectricBranch {
    double p, sin2T;
};
DielectricBranch dielectricBranch(const Item& it) {
    const dvec3 d = glm::normalize(dvec3(xyz(it.in[0]))), n(xyz(it.in[1]));
    const double ior = it.in[1].w, eta = it.in[2].x != 0.0f ? 1.0 / ior : ior;
    const double cosI = glm::clamp(-glm::dot(d, n), 0.0, 1.0);
    const double sin2T = eta * eta * (1.0 - cosI) * (1.0 + cosI);
    const double p = sin2T > 1.0 ? 1.0 : gpu::dielectricReflectProbability(float(cosI), float(eta), it.in[2].y != 0.0f);
    return {p, sin2T};
}

/// The refracted direction of scatterDielectric (its u >= probability branch), in double.
vec3 refracted(const Item& it) {
    const dvec3 d = glm::normalize(dvec3(xyz(it.in[0]))), n(xyz(it.in[1]));
    const double ior = it.in[1].w, eta = it.in[2].x != 0.0f ? 1.0 / ior : ior;
    const double cosI = glm::clamp(-glm::dot(d, n), 0.0, 1.0);
    const double cosT = std::sqrt(std::max(0.0, 1.0 - eta * eta * (1.0 - cosI) * (1.0 + cosI)));
    return vec3(glm::normalize(eta * d + (eta * cosI - cosT) * n));
}

TEST(GpuSampling, DielectricMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    UniformSource rng(110);
    const std::vector<vec3> normals = unitNormals(111, kRandomItems);
    const float iors[] = {1.5f, 1.33f, 2.4f, 1.0f, 1.0001f};
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const vec3 n = normals[i];
        const float ior = iors[i % 5];
        const bool front = (i / 5) % 2 == 0, exact = (i / 10) % 2 == 0;
        const double eta = front ? 1.0 / ior : ior;
        // Angles of incidence: uniform, normal, grazing, and at the critical angle (+- 1e-4 rad).
        double th = std::acos(1.0 - rng.next());
        const std::size_t kind = (i / 20) % 8;
        if (kind == 1) th = 0.0;
        if (kind == 2) th = kPi / 2 - 1e-4;
        if (kind == 3) th = kPi / 2;
        if (kind >= 4 && eta > 1.0) th = std::asin(1.0 / eta) + (double(kind) - 5.0) * 1e-4;
        const vec3 dIn = gpu::toWorld(gpu::onbFromNormal(n), vec3(float(std::sin(th)), 0.0f, -float(std::cos(th))));
        Item it = item(vec4(dIn, 0.0f), vec4(n, ior), vec4(front ? 1.0f : 0.0f, exact ? 1.0f : 0.0f, 0.0f, 0.0f));
        // u: uniform, the edges 0 and 1 - 2^-24, and exactly at the reflect probability
        const float edgesU[] = {0.0f, kBelowOne, float(dielectricBranch(it).p)};
        it.in[2].z = i % 4 == 3 ? edgesU[(i / 4) % 3] : rng.next();
        items.push_back(it);
    }
    checkRoutine(dev, kDielectric, "dielectric", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const vec3 dir = glm::normalize(xyz(it.in[0])), n = xyz(it.in[1]);
        const DielectricBranch b = dielectricBranch(it);
        // The refracted direction contains cosT = sqrt(1 - sin^2 T), sin^2 T = eta^2 (1 - cosI^2):
        // the last ulps of normalize(dIn) and of cosI give sin^2 T within dS = 1e-6 eta^2 (observed:
        // 1.1e-6 at eta = 2.4), which near the critical angle becomes min(dS / (2 cosT), sqrt(dS))
        // in cosT and in the direction.
        const double eta = it.in[2].x != 0.0f ? 1.0 / it.in[1].w : it.in[1].w, dS = 1e-6 * eta * eta;
        const double cosT = std::sqrt(std::max(0.0, 1.0 - b.sin2T));
        const double tol = kDirTol + std::min(dS / (2.0 * cosT), std::sqrt(dS));
        auto within = [&](vec3 a, vec3 e) { return glm::length(dvec3(a) - dvec3(e)) <= tol; };
        if (within(xyz(d.o[0]), xyz(h.o[0]))) {
            for (int k = 0; k < 3; ++k) c.near("dir", d.o[0][k], h.o[0][k], tol);
            return;
        }
        // The branch may differ where u is at the reflect probability, or at the critical angle.
        const bool undecided = std::fabs(it.in[2].z - b.p) < 1e-5 || std::fabs(b.sin2T - 1.0) < 1e-5;
        const bool hostReflected = glm::dot(xyz(h.o[0]), n) > 0.0f;
        const vec3 other = hostReflected ? refracted(it) : glm::reflect(dir, n);
        if (undecided && within(xyz(d.o[0]), other))
            c.flip();
        else
            for (int k = 0; k < 3; ++k) c.near("dir", d.o[0][k], h.o[0][k], tol);
    });
}

TEST(GpuSampling, FresnelMatchesHost) {
    VKP_REQUIRE_DEVICE(dev);
    std::vector<Item> items;
    const float cosines[] = {-1.5f, -1.0f, -0.7f, -0.0f, 0.0f, 1e-7f, 0.3f, 0.5f, 0.9f, 1.0f, 1.5f};
    const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 2.4f, 1.0f / 2.4f, 1.33f, 1.0001f, 0.9999f, 0.2f, 5.0f};
    for (float c : cosines)
        for (float e : etas) items.push_back(item(vec4(c, e, 0.0f, 0.0f)));
    UniformSource rng(120);
    for (int i = 0; i < kRandomItems; ++i) items.push_back(item(vec4(2.4f * rng.next() - 1.2f, 0.2f + 4.8f * rng.next(), 0.0f, 0.0f)));
    checkRoutine(dev, kFresnel, "fresnel", items, [](Compare& c, const Item& it, const Out& d, const Out& h) {
        const double cosI = glm::clamp(double(it.in[0].x), -1.0, 1.0), e = it.in[0].y;
        // sin^2 T of fresnelDielectricExact (e = eta_t / eta_i, inverted for cosI < 0) and of
        // dielectricReflectProbability (e = eta_i / eta_t, cosI clamped to [0, 1]).
        const double ee = cosI < 0.0 ? 1.0 / e : e;
        const double sin2Exact = (1.0 - cosI * cosI) / (ee * ee);
        const double cp = std::max(cosI, 0.0), sin2Prob = e * e * (1.0 - cp * cp);
        // At total internal reflection the reflectance is continuous (-> 1) but its slope is
        // infinite: an ulp of sin^2 T becomes min(1e-6 / (2 cosT), 1e-3) in cosT and in F.
        auto tolAt = [](double sin2) { return 1e-6 + std::min(1e-6 / (2.0 * std::sqrt(std::max(0.0, 1.0 - sin2))), 1e-3); };
        c.near("schlick", d.o[0].x, h.o[0].x, 1e-6);
        c.near("exact", d.o[0].y, h.o[0].y, tolAt(sin2Exact));
        // The Schlick value jumps to 1 at total internal reflection: either side there.
        if (d.o[0].z != h.o[0].z && (d.o[0].z == 1.0f || h.o[0].z == 1.0f) && std::fabs(sin2Prob - 1.0) < 1e-5)
            c.flip();
        else
            c.near("probSchlick", d.o[0].z, h.o[0].z, 1e-6);
        c.near("probExact", d.o[0].w, h.o[0].w, tolAt(sin2Prob));
    });
}

}  // namespace
}  // namespace vkp::test
