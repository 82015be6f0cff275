// Furnace tests of the integrator (label gpu): scenes whose every pixel has a closed-form value,
// rendered with every sampler (bsdf, light, mixture). Tolerances in standard errors from the
// per-pixel variance (test_gpu_analytic_common.h; budget declared in test_gpu_analytic_direct.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gpu_env.h"
#include "render/gpu_scene.h"
#include "test_gpu_analytic_common.h"
#include "file_frame.h"

namespace vkp::test {
namespace {


/// Direction (double) from the camera origin through the point (i, j) of the pixel grid
/// (pixel centres at integers, corners at +-0.5), as the kernel computes camera rays.
glm::dvec3 cameraTarget(const gpu::GpuFrame& f, double i, double j) {
    return glm::dvec3(f.pixel00) + i * glm::dvec3(f.pixelDu) + j * glm::dvec3(f.pixelDv);
}

/// True if the line o + t d (t > 0) passes within distance r of c.
bool rayNearSphere(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, double r) {
    d = glm::normalize(d);
    const glm::dvec3 f = c - o;
    const double b = glm::dot(f, d);
    return b > 0 && glm::length(f - b * d) < r;
}

// ---- Convex furnace ----------------------------------------------------------------------------
// A lambertian sphere (albedo a) under a uniform background of radiance 1 and nothing else: light
// reflected off a convex object never returns to it, so a pixel that sees only the sphere has
// expected value a exactly (the existing GpuRender test checks this without light sampling). Here
// the sphere is also "sample": true, so the light samplers run on it: from a point of its own
// surface its light pdf is the on-surface strategy (cosine lobe INTO the sphere):
//  - light: the sampled direction is below the shading normal (no contribution), the continuing
//    cosine ray sees the background: every sample is exactly a (zero variance);
//  - mixture: half of the samples pick the sphere's pdf, whose direction is below the surface (the
//    sample is 0), half the cosine lobe, weighted 2a (pdf 0.5 cos/pi + 0.5 * 0): mean a, variance a^2.
// Pixels that see only the background are exactly 1. Pixels on the silhouette are skipped.
TEST(GpuAnalytic, ConvexFurnaceWithSampledSphere) {
    VKP_REQUIRE_DEVICE(dev);
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 4], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 24, "height": 24},
      "render": {"max_depth": 50, "background": [1, 1, 1], "seed": 11},
      "materials": {"m": {"type": "lambertian", "albedo": [0.2, 0.5, 0.8]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m", "sample": true}]})",
                                 "convex-furnace.json");
    const glm::dvec3 albedo(0.2, 0.5, 0.8);
    gpu::GpuFrame f{};
    packFileFrameCamera(scene, f);
    const glm::dvec3 o(f.origin);
    std::vector<Pixel> inside, outside;
    for (std::uint32_t y = 0; y < 24; ++y)
        for (std::uint32_t x = 0; x < 24; ++x) {
            int hits = 0;
            for (double sx : {-0.5, 0.5})
                for (double sy : {-0.5, 0.5}) hits += rayNearSphere(o, cameraTarget(f, x + sx, y + sy) - o, glm::dvec3(0), 1.0);
            // All four corners on the sphere: the whole pixel is (the silhouette is convex).
            if (hits == 4) inside.push_back({x, y});
            // Outside: the sphere grown by one pixel's diagonal on the view plane (1.5 px margin).
            const double grow = 1.5 * glm::length(glm::dvec3(f.pixelDu)) * 4.0 / glm::length(cameraTarget(f, x, y) - o);
            if (!rayNearSphere(o, cameraTarget(f, x, y) - o, glm::dvec3(0), 1.0 + grow)) outside.push_back({x, y});
        }
    ASSERT_GT(inside.size(), 150u);
    ASSERT_GT(outside.size(), 150u);
    const std::uint32_t spp = 256;
    for (Sampler s : samplersUnderTest()) {
        const PixelStats st(renderSums(dev, scene, s, spp, "convex furnace"));
        const std::string name = samplerName(s);
        for (const Pixel& p : outside)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(st.mean.at(p.x, p.y, c), 1.0f) << name << " background at " << p.x << "," << p.y;
        for (int c = 0; c < 3; ++c) {
            if (s == Sampler::Bsdf || s == Sampler::Light) {
                // Zero variance: every pixel equals a up to float summation (n u |a|, see the header).
                for (const Pixel& p : inside)
                    ASSERT_NEAR(st.mean.at(p.x, p.y, c), albedo[c], spp * std::ldexp(1.0, -24) * albedo[c] + 1e-7)
                        << name << " " << p.x << "," << p.y;
            }
            EXPECT_TRUE(withinNoise(average(st, inside, c), albedo[c], name + " convex furnace, sphere pixels, " + kChannel[c], true));
            // Each quarter of the disc on its own (>= 40 pixels x 256 samples each).
            for (int q = 0; q < 4; ++q) {
                std::vector<Pixel> part;
                for (const Pixel& p : inside)
                    if (int(p.x >= 12) + 2 * int(p.y >= 12) == q) part.push_back(p);
                EXPECT_TRUE(withinNoise(average(st, part, c), albedo[c],
                                        name + " convex furnace quarter " + std::to_string(q) + " " + kChannel[c]));
            }
        }
    }
}

// ---- Closed furnace ----------------------------------------------------------------------------
// The camera inside a closed sphere; inside it also a sphere, a two-sided quad and a triangle
// floating free. Every surface is the same emitting lambertian (albedo a, emission Le, both faces),
// and every one is in the light list (emitters are sampled). Every ray hits a surface whose outgoing
// radiance solves L = Le + a L, so L = Le / (1 - a) everywhere (the uniform solution of the
// rendering equation of a closed scene; the geometry does not matter). Next-event estimation from
// the outer sphere's own surface uses the on-surface strategy, from the inner objects its "inside"
// strategy, and the inner sphere is sampled by its cone: the cases where the book's sphere pdf
// gives NaN.
//
// Depth: the kernel traces at most max_depth = D rays per path (the camera ray included), adds
// the emission found at each hit, and does not scatter (nor estimate direct light) at the D-th
// hit, so every sampler collects D emission events: Le (1 + a + ... + a^(D-1)) = Le (1 - a^D) /
// (1 - a) in expectation (Russian roulette is unbiased). Next-event estimation at the D-th vertex
// would add one more bounce, Le (1 - a^(D+1)) / (1 - a): D = 3 pins that all samplers agree on the
// meaning of max_depth; D = 64 is the untruncated answer Le / (1 - a) to within 0.7^64 ~ 1e-10.
Scene closedFurnace(std::uint32_t maxDepth, std::uint32_t seed) {
    Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 0, 1.5], "lookat": [0, 0, -1], "vup": [0, 1, 0], "vfov": 70, "width": 16, "height": 16},
      "render": {"max_depth": 3, "background": [0, 0, 0]},
      "materials": {"wall": {"type": "lambertian", "albedo": [0.3, 0.5, 0.7], "emit": [1, 0.5, 0.25]}},
      "objects": [
        {"type": "sphere", "center": [0, 0, 0], "radius": 3, "material": "wall"},
        {"type": "sphere", "center": [1, 0.3, -1.2], "radius": 0.6, "material": "wall"},
        {"type": "quad", "Q": [-1.5, -1, -1.5], "u": [1, 0, 0.3], "v": [0, 1.2, 0], "material": "wall"},
        {"type": "triangle", "v0": [-0.5, 1, -1], "v1": [0.5, 1.6, -1.3], "v2": [0, 1.2, -0.2], "material": "wall"}
      ]})",
                                 "closed-furnace.json");
    scene.render.maxDepth = maxDepth;
    scene.render.seed = seed;
    return scene;
}

TEST(GpuAnalytic, ClosedFurnaceEqualsTruncatedGeometricSeries) {
    VKP_REQUIRE_DEVICE(dev);
    const glm::dvec3 a(0.3, 0.5, 0.7), le(1.0, 0.5, 0.25);
    const std::uint32_t spp = 1024;
    for (std::uint32_t depth : {3u, 64u}) {
        for (Sampler s : samplersUnderTest()) {
            const Scene scene = closedFurnace(depth, 100 + depth + std::uint32_t(s));
            const PixelStats st(renderSums(dev, scene, s, spp, "closed furnace"));
            const std::string name = std::string(samplerName(s)) + " closed furnace, max_depth " + std::to_string(depth);
            for (int c = 0; c < 3; ++c) {
                const double expected = le[c] * (1.0 - std::pow(a[c], depth)) / (1.0 - a[c]);
                EXPECT_TRUE(withinNoise(average(st, rect(0, 0, 16, 16), c), expected, name + ", image, " + kChannel[c], true));
                for (std::uint32_t by = 0; by < 16; by += 8)
                    for (std::uint32_t bx = 0; bx < 16; bx += 8)
                        EXPECT_TRUE(withinNoise(average(st, rect(bx, by, bx + 8, by + 8), c), expected,
                                                name + ", block " + std::to_string(bx) + "," + std::to_string(by) + ", " + kChannel[c]));
            }
        }
    }
}

}  // namespace
}  // namespace vkp::test
