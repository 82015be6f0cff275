// Beer-Lambert absorption inside dielectrics (issue 16, "Dielectrics with an interior"): a glass
// sphere seen along its axis against the closed form of its internal reflections, under every
// sampler; and next-event estimation from inside absorbing glass (shadow rays attenuated) against
// BSDF sampling alone, which attenuates only path segments.
//
// Statistics: z-tests of pooled pixel means with the variance estimated from the sums; |z| <= 4.5
// per test, a false-failure probability of about 7e-6 each (normal tails; 12 + 3 tests here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gpu_env.h"
#include "render_helpers.h"
#include "scene/scene.h"

namespace vkp::test {
namespace {

constexpr double kMaxZ = 4.5;

// Glass of index 1.5 (F = 0.04 at normal incidence), radius 1, seen along its axis through a
// 0.01-degree field of view against a background of 1: a camera ray is reflected (F, sees 1) or
// enters, crosses 2R (keeps a = exp(-2 sigma R)), and leaves or is reflected back, and so on:
// the pixel is F + (1 - F)^2 a / (1 - F a). Three absorptions per render, one per channel.
TEST(GpuAbsorption, GlassSphereAlongItsAxisMatchesTheClosedForm) {
    VKP_REQUIRE_DEVICE(dev);
    const double sigmas[2][3] = {{0.0, 0.1, 0.5}, {1.0, 2.0, 4.0}};
    // Every sampler takes the same paths here (a delta BSDF and a background: no light sampling),
    // so two of them suffice.
    for (const auto& sigma : sigmas) {
        char json[1024];
        std::snprintf(json, sizeof json, R"({
          "camera": {"lookfrom": [0, 0, 10], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 0.01, "width": 3, "height": 3},
          "render": {"max_depth": 64, "background": [1, 1, 1]},
          "materials": {"glass": {"type": "dielectric", "ior": 1.5, "absorption": [%g, %g, %g]}},
          "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}]})",
                      sigma[0], sigma[1], sigma[2]);
        const Scene scene = parseSceneJson(json, "absorbing-sphere.json");
        for (Sampler sampler : {Sampler::Bsdf, Sampler::Mis}) {
            const PixelSums s = renderSums(dev, scene, sampler, 4096, "absorbing sphere");
            for (int c = 0; c < 3; ++c) {
                const double F = 0.04, a = std::exp(-2.0 * sigma[c]);
                const double want = F + (1 - F) * (1 - F) * a / (1 - F * a);
                double mean, se;
                pooledMean(s, c, mean, se);
                const double z = (mean - want) / std::max(se, 1e-9);
                std::printf("  %-7s sigma %-4g: %.6f vs closed form %.6f (z %.2f)\n", samplerName(sampler), sigma[c], mean, want, z);
                EXPECT_LE(std::abs(z), kMaxZ) << samplerName(sampler) << " sigma " << sigma[c];
            }
        }
    }
}

// A small emitting sphere and a diffuse floor inside a large absorbing glass sphere. `bsdf` sampling
// finds the light only by path segments, each attenuated; `light` and `mis` also reach it by
// shadow rays, which must be attenuated by their length as well: the images' means agree.
TEST(GpuAbsorption, NextEventEstimationInsideGlassIsAttenuatedToo) {
    VKP_REQUIRE_DEVICE(dev);
    // Index 1 with exact Fresnel: the glass neither bends nor reflects, it only absorbs, so the
    // camera sees the floor, whose light is mostly next-event estimation's (a small lamp).
    const Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 2, 5.5], "lookat": [0, -1, 0], "vup": [0, 1, 0], "vfov": 30, "width": 16, "height": 16},
      "render": {"max_depth": 16, "background": [0, 0, 0]},
      "materials": {"glass": {"type": "dielectric", "ior": 1.0, "fresnel": "exact", "absorption": [0.1, 0.4, 1.2]},
                    "floor": {"type": "lambertian", "albedo": [0.8, 0.8, 0.8]},
                    "lamp": {"type": "diffuse_light", "emit": [20, 20, 20]}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 3, "material": "glass"},
                  {"type": "quad", "Q": [-1.5, -1, 1.5], "u": [3, 0, 0], "v": [0, 0, -3], "material": "floor"},
                  {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.2, "material": "lamp"}]})",
                                       "glass-room.json");
    expectSamplersAgreeWithBsdf(dev, scene, 4096, 1024, "glass room", kMaxZ, 1e-3);
}

}  // namespace
}  // namespace vkp::test
