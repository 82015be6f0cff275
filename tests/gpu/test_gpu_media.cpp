// Constant-density media (issue 16; shared/medium.h, lib/media.glsl) against closed forms and
// against each other:
//   - the white furnace: a medium of albedo 1 under a background of 1 is invisible (every pixel 1),
//     seen from outside, from inside and where media overlap, under every sampler;
//   - absorbing media (albedo 0) in front of a background of 1 leave exp(-density x length), for
//     slabs of several thicknesses, a rotated box, a sphere's chord, overlapping media (densities
//     add) and a camera inside a medium;
//   - next-event estimation from inside a medium (shadow rays weighted by transmittance, MIS with
//     the phase function) agrees with phase-function sampling alone (`bsdf`, the book's method) in a
//     lit scattering medium, for quad, sphere and punctual lights and the environment;
//   - a medium whose albedo is a solid texture renders the bits of the same constant albedo.
//
// Statistics: z-tests of pooled pixel means with the variance estimated from the sums; |z| <= 4.5
// per test, a false-failure probability of about 7e-6 each (normal tails; about 60 tests here,
// 4e-4 together). Fixed seeds (the scenes' default seed 0): a run's result is reproducible.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "gpu_env.h"
#include "render_helpers.h"
#include "sums_agreement.h"
#include "scene/scene.h"

namespace vkp::test {
namespace {

constexpr double kMaxZ = 4.5;

/// |mean - want| / se of channel c over every pixel of s, printed with `what`.
double zAgainst(const PixelSums& s, int c, double want, const std::string& what) {
    double mean, se;
    pooledMean(s, c, mean, se);
    const double z = (mean - want) / std::max(se, 1e-12);
    std::printf("  %-44s channel %d: %.6f vs %.6f (z %.2f)\n", what.c_str(), c, mean, want, z);
    return z;
}

/// A scene of only `objects` (JSON array members) seen from `from` towards `at` with a field of
/// view of vfov degrees, `size` pixels square, under a background of 1.
Scene mediaScene(const std::string& objects, const char* from, const char* at, double vfov, int size) {
    char head[512];
    std::snprintf(head, sizeof head,
                  R"({"camera": {"lookfrom": %s, "lookat": %s, "vup": [0, 1, 0], "vfov": %g, "width": %d, "height": %d},
                      "render": {"max_depth": 1024, "background": [1, 1, 1]}, "objects": [)",
                  from, at, vfov, size, size);
    return parseSceneJson(std::string(head) + objects + "]}", "media.json");
}

// White furnace: albedo 1 and a background of 1 on every side: whatever the path does inside, it
// carries 1 out, so every pixel is 1 (max_depth 1024 is far beyond the scatterings of these
// optical depths, at most 8 to the centre). Seen from outside, from inside, and with overlapping
// media (the densities add).
TEST(GpuMedia, WhiteFurnaceIsInvisibleUnderEverySampler) {
    VKP_REQUIRE_DEVICE(dev);
    const struct {
        const char* name;
        const char* from;
        std::string objects;
    } cases[] = {
        {"sphere, density 2, from outside", "[0, 0, 5]",
         R"({"type": "constant_medium", "density": 2, "albedo": [1, 1, 1],
             "boundary": {"type": "sphere", "center": [0, 0, 0], "radius": 1}})"},
        {"ellipsoid, density 8, camera inside", "[0, 0, 0.2]",
         R"({"type": "constant_medium", "density": 8, "albedo": [1, 1, 1],
             "boundary": {"type": "sphere", "center": [0, 0, 0], "radius": 1, "transform": [{"scale": [1, 0.5, 1]}]}})"},
        {"box and sphere overlapping", "[0.3, 0.2, 4]",
         R"({"type": "constant_medium", "density": 1.5, "albedo": [1, 1, 1],
             "boundary": {"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "transform": [{"rotate_y": 30}]}},
            {"type": "constant_medium", "density": 3, "albedo": [1, 1, 1],
             "boundary": {"type": "sphere", "center": [0.5, 0, 0.5], "radius": 0.8}})"},
    };
    for (const auto& c : cases) {
        const Scene scene = mediaScene(c.objects, c.from, "[0, 0, 0]", 40, 10);
        for (Sampler sampler : kAllSamplers) {
            const PixelSums s = renderSums(dev, scene, sampler, 192, c.name);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_LE(std::abs(zAgainst(s, ch, 1.0, std::string(c.name) + " " + samplerName(sampler))), kMaxZ)
                    << c.name << " " << samplerName(sampler) << " channel " << ch;
            }
        }
    }
}

// Purely absorbing media (albedo 0) seen along the z axis through a 0.01-degree field of view
// against a background of 1: a sample is 1 with probability exp(-optical depth), else 0.
TEST(GpuMedia, AbsorbingMediaLeaveTheirTransmittance) {
    VKP_REQUIRE_DEVICE(dev);
    const struct {
        const char* name;
        const char* from;
        std::string objects;
        double depth;  // optical depth along the axis
    } cases[] = {
        {"slab 0.5 thick, density 0.5", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 0.5, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, -0.25], "max": [5, 5, 0.25]}})",
         0.25},
        {"slab 2 thick, density 0.5", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 0.5, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, -1], "max": [5, 5, 1]}})",
         1.0},
        {"slab 0.1 thick, density 25", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 25, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, 0], "max": [5, 5, 0.1]}})",
         2.5},
        // A cube turned 45 degrees about y and seen along z: the path through its centre is the
        // diagonal of its square cross-section, sqrt(2) x 1.
        {"cube turned 45 degrees, diagonal", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 0.7, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5], "transform": [{"rotate_y": 45}]}})",
         0.7 * std::sqrt(2.0)},
        {"sphere, chord through the centre", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 0.4, "albedo": [0, 0, 0],
             "boundary": {"type": "sphere", "center": [0, 0, 0], "radius": 1.5}})",
         0.4 * 3.0},
        {"overlapping slabs: densities add", "[0, 0, 10]",
         R"({"type": "constant_medium", "density": 0.3, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, -1], "max": [5, 5, 1]}},
            {"type": "constant_medium", "density": 0.6, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, 0], "max": [5, 5, 2]}})",
         0.3 * 2.0 + 0.6 * 2.0},
        {"camera inside, 3 to the exit face", "[0, 0, 1]",
         R"({"type": "constant_medium", "density": 0.25, "albedo": [0, 0, 0],
             "boundary": {"type": "box", "min": [-5, -5, -2], "max": [5, 5, 2]}})",
         0.25 * 3.0},
    };
    for (const auto& c : cases) {
        const Scene scene = mediaScene(c.objects, c.from, "[0, 0, -10]", 0.01, 4);
        const double want = std::exp(-c.depth);
        // Every sampler takes the same paths (an absorbed path carries nothing): `mis`, whose
        // next-event estimation of the background runs too (and adds nothing at albedo 0).
        for (Sampler sampler : {Sampler::Mis}) {
            const PixelSums s = renderSums(dev, scene, sampler, 2048, c.name);
            EXPECT_LE(std::abs(zAgainst(s, 0, want, std::string(c.name) + " " + samplerName(sampler))), kMaxZ)
                << c.name << " " << samplerName(sampler);
        }
    }
}

// A scattering medium (albedo 0.8, 0.6, 0.4) in a room lit by a quad light, a sphere light, a point
// light and the environment through an open side: `bsdf` finds the lights only by phase-function
// and BSDF samples (the book's method); `light`, `mixture` and `mis` also send shadow rays from
// points inside the medium and from surfaces behind it, which must be weighted by the media's
// transmittance (and, under `mis`, by MIS against the phase function). The images' means agree.
TEST(GpuMedia, NextEventEstimationInMediaAgreesWithPhaseSampling) {
    VKP_REQUIRE_DEVICE(dev);
    const Scene scene = parseSceneJson(R"({
      "camera": {"lookfrom": [0, 1, 6], "lookat": [0, 1, 0], "vup": [0, 1, 0], "vfov": 50, "width": 16, "height": 16},
      "render": {"max_depth": 32, "background": [0.3, 0.4, 0.5]},
      "materials": {"floor": {"type": "lambertian", "albedo": [0.7, 0.7, 0.7]},
                    "panel": {"type": "diffuse_light", "emit": [6, 6, 6]},
                    "bulb": {"type": "diffuse_light", "emit": [30, 20, 10]}},
      "objects": [{"type": "quad", "Q": [-3, 0, 3], "u": [6, 0, 0], "v": [0, 0, -6], "material": "floor"},
                  {"type": "quad", "Q": [-1, 3, -1], "u": [2, 0, 0], "v": [0, 0, 2], "material": "panel"},
                  {"type": "sphere", "center": [1.2, 1.5, 0.5], "radius": 0.15, "material": "bulb"},
                  {"type": "point_light", "position": [-1.5, 1.2, 0.5], "intensity": [3, 3, 3]},
                  {"type": "constant_medium", "density": 0.6, "albedo": [0.8, 0.6, 0.4],
                   "boundary": {"type": "box", "min": [-1.5, 0, -1.5], "max": [1.5, 2.5, 1.5], "transform": [{"rotate_y": 20}]}},
                  {"type": "constant_medium", "density": 1.5, "albedo": [0.9, 0.9, 0.9],
                   "boundary": {"type": "sphere", "center": [-0.5, 1, 1], "radius": 0.6}}]})",
                                       "lit-medium.json");
    expectSamplersAgreeWithBsdf(dev, scene, 2048, 512, "lit medium", kMaxZ, 1e-2);
}

// Shadow rays of punctual lights cross media too (under every sampler: `bsdf` and `mixture` sample
// punctual lights by next-event estimation as well). A directional light straight down through a
// horizontal absorbing slab onto a floor, seen from between them: every sample is the slab-free
// sample times exp(-density x thickness) (the shadow ray is the only light; the floor's own
// samples leave upwards through the slab into a black background), to float precision.
TEST(GpuMedia, PunctualShadowRaysAreAttenuated) {
    VKP_REQUIRE_DEVICE(dev);
    const char* head = R"({
      "camera": {"lookfrom": [0, 1, 2], "lookat": [0, 0, 0], "vup": [0, 1, 0], "vfov": 40, "width": 8, "height": 8},
      "render": {"max_depth": 8, "background": [0, 0, 0]},
      "materials": {"floor": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"type": "quad", "Q": [-10, 0, 10], "u": [20, 0, 0], "v": [0, 0, -20], "material": "floor"},
                  {"type": "directional_light", "direction": [0, -1, 0], "irradiance": [2, 2, 2]})";
    const char* slab = R"(, {"type": "constant_medium", "density": 0.8, "albedo": [0, 0, 0],
                             "boundary": {"type": "box", "min": [-20, 3, -20], "max": [20, 4.5, 20]}})";
    const double want = std::exp(-0.8 * 1.5);
    for (Sampler sampler : {Sampler::Bsdf, Sampler::Mis}) {  // the punctual-only and the power-pick routes
        const PixelSums open = renderSums(dev, parseSceneJson(std::string(head) + "]}", "open.json"), sampler, 16, "open");
        const PixelSums shaded = renderSums(dev, parseSceneJson(std::string(head) + slab + "]}", "slab.json"), sampler, 16, "slab");
        double worst = 0.0, lit = 0.0;
        for (std::size_t i = 0; i < open.sum.size(); ++i) {
            if (i % 4 == 3) continue;
            lit = std::max(lit, open.sum[i]);
            if (open.sum[i] > 0.0) worst = std::max(worst, std::abs(shaded.sum[i] / open.sum[i] - want));
        }
        std::printf("  %-7s worst |ratio - exp(-1.2)| %.2e\n", samplerName(sampler), worst);
        EXPECT_GT(lit, 0.0) << samplerName(sampler) << ": the floor is lit";
        EXPECT_LE(worst, 1e-5) << samplerName(sampler);
    }
}

// The albedo of a medium may be a texture: a solid texture of colour C gives the bits of the
// constant albedo C (the same paths, the same arithmetic; only the variant differs), or the same
// samples up to rounding on a device that rounds otherwise than the host (sums_agreement.h).
TEST(GpuMedia, SolidTextureAlbedoEqualsTheConstant) {
    VKP_REQUIRE_DEVICE(dev);
    const char* albedos[2] = {R"([0.9, 0.5, 0.25])", R"({"type": "solid", "color": [0.9, 0.5, 0.25]})"};
    PixelSums sums[2];
    for (int i = 0; i < 2; ++i) {
        const Scene scene = mediaScene(std::string(R"({"type": "constant_medium", "density": 2, "albedo": )") + albedos[i] +
                                           R"(, "boundary": {"type": "sphere", "center": [0, 0, 0], "radius": 1}})",
                                       "[0, 0, 4]", "[0, 0, 0]", 40, 8);
        sums[i] = renderSums(dev, scene, Sampler::Mis, 64, i ? "textured albedo" : "constant albedo");
    }
    double mean, se;
    pooledMean(sums[0], 2, mean, se);
    EXPECT_LT(mean, 0.99) << "the medium is visible";
    EXPECT_TRUE(sameSamples(dev, sums[0], sums[1], "solid texture albedo against the constant"));
}

}  // namespace
}  // namespace vkp::test
